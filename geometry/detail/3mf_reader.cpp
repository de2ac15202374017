// The one translation unit that includes lib3mf (its plain C interface of version 1.x).
#include "geometry/detail/3mf_reader.hpp"

// lib3mf's header declares the lib3mf_* functions in namespace NMR with its own Windows-style
// types (DWORD, BOOL, LPCSTR, ...).
#include <Model/COM/NMR_DLLInterfaces.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "geometry/detail/text_scan.hpp"

// lib3mf 1.8.1 never closes the ZIP entries it opens with libzip (160 bytes per package part
// read, freed by no call of its interface), so LeakSanitizer would report every 3MF read. The
// suppression is compiled into sanitizer builds only and names libzip alone, so leaks of
// bemshape's own code are still reported.
#if defined(__SANITIZE_ADDRESS__)
#define BEMSHAPE_LSAN_SUPPRESSIONS 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BEMSHAPE_LSAN_SUPPRESSIONS 1
#endif
#endif
#ifdef BEMSHAPE_LSAN_SUPPRESSIONS
extern "C" const char* __lsan_default_suppressions() { return "leak:libzip.so\n"; }
#endif

namespace bemshape::geometry::detail {
namespace {

namespace fs = std::filesystem;

/// Owns one lib3mf instance (model, reader, iterator, build item, object, component): every
/// instance the interface returns must be released exactly once.
class Instance {
 public:
  Instance() = default;
  ~Instance() { reset(); }
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;
  Instance(Instance&& other) noexcept : p_(other.p_) { other.p_ = nullptr; }

  NMR::PLib3MFBase* get() const { return p_; }
  /// For the functions that return a new instance through a pointer argument.
  NMR::PLib3MFBase** out() {
    reset();
    return &p_;
  }

 private:
  void reset() {
    if (p_ != nullptr)
      NMR::lib3mf_release(p_);
    p_ = nullptr;
  }
  NMR::PLib3MFBase* p_ = nullptr;
};

/// What went wrong according to lib3mf: its last error message on `instance`, with the code.
std::string lib3mf_error(NMR::PLib3MFBase* instance, LIB3MFRESULT result) {
  DWORD code = 0;
  LPCSTR message = nullptr;
  if (instance != nullptr)
    NMR::lib3mf_getlasterror(instance, &code, &message);
  char hex[32];
  std::snprintf(hex, sizeof hex, "0x%x", code != 0 ? static_cast<unsigned>(code)
                                                   : static_cast<unsigned>(result));
  std::string text = message != nullptr && *message != '\0' ? message : "unknown error";
  return text + " (lib3mf error " + hex + ")";
}

/// An affine map x ↦ R x + t.
struct Affine {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Affine operator*(const Affine& inner) const { return {R * inner.R, R * inner.t + t}; }
};

Affine to_affine(const NMR::MODELTRANSFORM& m) {
  Affine a;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      a.R(i, j) = m.m_fFields[i][j];
    a.t(i) = m.m_fFields[i][3];
  }
  return a;
}

class Reader {
 public:
  Reader(const fs::path& path, TriangleSoup& soup) : path_(path), soup_(soup) {}

  void read(std::string_view bytes) {
    Instance model;
    check(NMR::lib3mf_createmodel(model.out()), nullptr, "cannot create a 3MF model");
    Instance reader;
    check(NMR::lib3mf_model_queryreader(model.get(), "3mf", reader.out()), model.get(),
          "cannot create a 3MF reader");
    // lib3mf only reads the buffer; its interface takes it as non-const.
    auto* data = reinterpret_cast<BYTE*>(const_cast<char*>(bytes.data()));
    const LIB3MFRESULT result =
        NMR::lib3mf_reader_readfrombuffer(reader.get(), data, bytes.size());
    if (result != 0)
      fail(path_, "cannot be read as a 3MF package: " + lib3mf_error(reader.get(), result));

    DWORD unit = NMR::MODELUNIT_MILLIMETER;
    check(NMR::lib3mf_model_getunit(model.get(), &unit), model.get(), "cannot read the unit");
    soup_.unit = unit_name(unit);
    soup_.millimetres_per_unit = millimetres_per_3mf_unit(soup_.unit);

    Instance items;
    check(NMR::lib3mf_model_getbuilditems(model.get(), items.out()), model.get(),
          "cannot list the build items");
    BOOL has_next = false;
    std::size_t k = 0;
    while (true) {
      check(NMR::lib3mf_builditemiterator_movenext(items.get(), &has_next), items.get(),
            "cannot list the build items");
      if (!has_next)
        break;
      ++k;
      Instance item;
      check(NMR::lib3mf_builditemiterator_getcurrent(items.get(), item.out()), items.get(),
            "cannot read build item " + std::to_string(k));
      Affine transform;
      BOOL has_transform = false;
      check(NMR::lib3mf_builditem_hasobjecttransform(item.get(), &has_transform), item.get(),
            "cannot read build item " + std::to_string(k));
      if (has_transform) {
        NMR::MODELTRANSFORM m;
        check(NMR::lib3mf_builditem_getobjecttransform(item.get(), &m), item.get(),
              "cannot read the transform of build item " + std::to_string(k));
        transform = to_affine(m);
      }
      Instance object;
      check(NMR::lib3mf_builditem_getobjectresource(item.get(), object.out()), item.get(),
            "cannot read the object of build item " + std::to_string(k));
      const std::string where = "build item " + std::to_string(k);
      check_transform(transform, where);
      place(object, transform, where, 0);
    }
    soup_.build_items = k;
    if (k == 0)
      fail(path_, "the 3MF build has no items, so the file places no part; add the objects to "
                  "the build in the exporting program");
    soup_.vertices.resize(static_cast<Eigen::Index>(points_.size()), 3);
    for (std::size_t v = 0; v < points_.size(); ++v)
      soup_.vertices.row(static_cast<Eigen::Index>(v)) = points_[v].transpose();
    soup_.faces.resize(static_cast<Eigen::Index>(triangles_.size()), 3);
    for (std::size_t f = 0; f < triangles_.size(); ++f)
      for (int c = 0; c < 3; ++c)
        soup_.faces(static_cast<Eigen::Index>(f), c) = triangles_[f][static_cast<std::size_t>(c)];
    if (soup_.mesh_instances == 0)
      fail(path_, "the 3MF build places no object of type \"model\" (only supports or other "
                  "objects), so there is no part");
  }

 private:
  void check(LIB3MFRESULT result, NMR::PLib3MFBase* instance, const std::string& what) {
    if (result != 0)
      fail(path_, what + ": " + lib3mf_error(instance, result));
  }

  static std::string unit_name(DWORD unit) {
    switch (unit) {
      case NMR::MODELUNIT_MICROMETER:
        return "micron";
      case NMR::MODELUNIT_MILLIMETER:
        return "millimeter";
      case NMR::MODELUNIT_CENTIMETER:
        return "centimeter";
      case NMR::MODELUNIT_INCH:
        return "inch";
      case NMR::MODELUNIT_FOOT:
        return "foot";
      case NMR::MODELUNIT_METER:
        return "meter";
      default:
        return "";
    }
  }

  /// "object 3" or "object 3 ('bracket')".
  std::string object_label(NMR::PLib3MFBase* object, DWORD id) {
    std::string label = "object id " + std::to_string(id);
    ULONG needed = 0;
    if (NMR::lib3mf_object_getnameutf8(object, nullptr, 0, &needed) == 0 && needed > 0) {
      std::vector<char> name(needed + 1, '\0');
      if (NMR::lib3mf_object_getnameutf8(object, name.data(), static_cast<ULONG>(name.size()),
                                         &needed) == 0 &&
          name[0] != '\0')
        label += " ('" + std::string(name.data()) + "')";
    }
    return label;
  }

  void check_transform(const Affine& a, const std::string& where) {
    if (!a.R.allFinite() || !a.t.allFinite())
      fail(path_, where + ": the transform has a non-finite entry; the file is corrupt");
    // A singular R flattens the object onto a plane or line: no solid is left. The test is
    // relative to the scale of R, so tiny and huge unit scalings both pass.
    const double scale = a.R.cwiseAbs().maxCoeff();
    if (!(std::abs(a.R.determinant()) > 1e-12 * scale * scale * scale))
      fail(path_, where + ": the transform is singular (determinant " +
                      std::to_string(a.R.determinant()) +
                      "), it would flatten the object; fix the placement in the exporting "
                      "program");
  }

  void place(const Instance& object, const Affine& transform, const std::string& where,
             int depth) {
    DWORD id = 0;
    check(NMR::lib3mf_resource_getresourceid(object.get(), &id), object.get(),
          where + ": cannot read the object id");
    const std::string label = where + ", " + object_label(object.get(), id);
    if (depth > kMax3mfComponentDepth)
      fail(path_, label + ": components are nested more than " +
                      std::to_string(kMax3mfComponentDepth) +
                      " levels deep (a cycle of components?); the file is corrupt");
    BOOL is_mesh = false, is_components = false;
    check(NMR::lib3mf_object_ismeshobject(object.get(), &is_mesh), object.get(), label);
    check(NMR::lib3mf_object_iscomponentsobject(object.get(), &is_components), object.get(),
          label);
    if (is_components) {
      DWORD count = 0;
      check(NMR::lib3mf_componentsobject_getcomponentcount(object.get(), &count), object.get(),
            label + ": cannot count its components");
      for (DWORD c = 0; c < count; ++c) {
        const std::string component_where = label + ", component " + std::to_string(c + 1);
        Instance component;
        check(NMR::lib3mf_componentsobject_getcomponent(object.get(), c, component.out()),
              object.get(), component_where);
        Affine inner;
        BOOL has_transform = false;
        check(NMR::lib3mf_component_hastransform(component.get(), &has_transform),
              component.get(), component_where);
        if (has_transform) {
          NMR::MODELTRANSFORM m;
          check(NMR::lib3mf_component_gettransform(component.get(), &m), component.get(),
                component_where + ": cannot read the transform");
          inner = to_affine(m);
        }
        check_transform(inner, component_where);
        Instance child;
        check(NMR::lib3mf_component_getobjectresource(component.get(), child.out()),
              component.get(), component_where + ": cannot read the object it places");
        place(child, transform * inner, component_where, depth + 1);
      }
      return;
    }
    if (!is_mesh)
      fail(path_, label + ": neither a mesh nor a components object (a slice stack or another "
                          "extension's object), which bemshape cannot read as a surface");

    DWORD type = NMR::MODELOBJECTTYPE_MODEL;
    check(NMR::lib3mf_object_gettype(object.get(), &type), object.get(), label);
    if (type != NMR::MODELOBJECTTYPE_MODEL) {
      const char* name = type == NMR::MODELOBJECTTYPE_SUPPORT        ? "support"
                         : type == NMR::MODELOBJECTTYPE_SOLIDSUPPORT ? "solidsupport"
                         : type == NMR::MODELOBJECTTYPE_SURFACE      ? "surface"
                                                                     : "other";
      soup_.notes.push_back(label + " is of type \"" + name +
                            "\", not \"model\": skipped, it is not part of the solid");
      return;
    }
    add_mesh(object.get(), transform, label);
  }

  void add_mesh(NMR::PLib3MFBase* mesh, const Affine& transform, const std::string& label) {
    DWORD beams = 0;
    check(NMR::lib3mf_meshobject_getbeamcount(mesh, &beams), mesh, label);
    if (beams > 0)
      fail(path_, label + ": has a beam lattice (" + std::to_string(beams) +
                      (beams == 1 ? " beam" : " beams") + "), which bemshape cannot represent as a triangle surface; export "
                      "the lattice as a mesh");
    DWORD nv = 0, nt = 0;
    check(NMR::lib3mf_meshobject_getvertexcount(mesh, &nv), mesh, label);
    check(NMR::lib3mf_meshobject_gettrianglecount(mesh, &nt), mesh, label);
    if (nt == 0)
      fail(path_, label + ": the mesh object has no triangles (" + std::to_string(nv) +
                      " vertices); export the part as a closed triangle mesh");
    std::vector<NMR::MODELMESHVERTEX> vertices(nv);
    std::vector<NMR::MODELMESHTRIANGLE> triangles(nt);
    DWORD got = 0;
    check(NMR::lib3mf_meshobject_getvertices(mesh, vertices.data(), nv, &got), mesh,
          label + ": cannot read the vertices");
    check(NMR::lib3mf_meshobject_gettriangleindices(mesh, triangles.data(), nt, &got), mesh,
          label + ": cannot read the triangles");

    const std::size_t v0 = points_.size();
    constexpr auto kMaxIndex = static_cast<std::size_t>(std::numeric_limits<int>::max());
    if (v0 + nv > kMaxIndex || triangles_.size() + nt > kMaxIndex)
      fail(path_, label + ": the build places more than 2^31 vertices or triangles: the part "
                          "is too large");
    for (DWORD v = 0; v < nv; ++v) {
      const Eigen::Vector3d p(vertices[v].m_fPosition[0], vertices[v].m_fPosition[1],
                              vertices[v].m_fPosition[2]);
      if (!p.allFinite())
        fail(path_, label + ", vertex " + std::to_string(v) +
                        ": a coordinate is not finite; the file is corrupt");
      points_.push_back(transform.R * p + transform.t);
    }
    // A mirroring transform turns the surface inside out; reversing the corner order keeps
    // the orientation the file gave the object.
    const bool mirrored = transform.R.determinant() < 0.0;
    for (DWORD t = 0; t < nt; ++t) {
      std::array<int, 3> corner{};
      for (int c = 0; c < 3; ++c) {
        const DWORD index = triangles[t].m_nIndices[c];
        if (index >= nv)
          fail(path_, label + ", triangle " + std::to_string(t) + ": refers to vertex " +
                          std::to_string(index) + " but the object has " + std::to_string(nv) +
                          " vertices (counted from 0); the file is corrupt");
        corner[static_cast<std::size_t>(c)] = static_cast<int>(v0 + index);
      }
      if (mirrored)
        std::swap(corner[1], corner[2]);
      triangles_.push_back(corner);
    }
    soup_.corners_in_file += 3 * static_cast<std::size_t>(nt);
    ++soup_.mesh_instances;
  }

  const fs::path& path_;
  TriangleSoup& soup_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::array<int, 3>> triangles_;
};

}  // namespace

double millimetres_per_3mf_unit(std::string_view unit) {
  if (unit == "micron")
    return 1e-3;
  if (unit == "millimeter")
    return 1.0;
  if (unit == "centimeter")
    return 10.0;
  if (unit == "inch")
    return 25.4;
  if (unit == "foot")
    return 304.8;
  if (unit == "meter")
    return 1000.0;
  return 0.0;
}

void read_3mf(const fs::path& path, std::string_view bytes, TriangleSoup& soup) {
  soup.format = "3MF";
  Reader(path, soup).read(bytes);
}

}  // namespace bemshape::geometry::detail
