#include "tests/support/model_3mf_writer.hpp"

#include <Model/COM/NMR_DLLInterfaces.h>

#include <stdexcept>

namespace bemshape::testing {
namespace {

void check(LIB3MFRESULT result, const char* what) {
  if (result != 0)
    throw std::runtime_error(std::string("lib3mf writer: ") + what + " failed");
}

NMR::MODELTRANSFORM to_model_transform(const Eigen::Affine3d& a) {
  NMR::MODELTRANSFORM m{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j)
      m.m_fFields[i][j] = static_cast<float>(a.matrix()(i, j));
  return m;
}

DWORD unit_code(const std::string& unit) {
  if (unit == "micron")
    return NMR::MODELUNIT_MICROMETER;
  if (unit == "millimeter")
    return NMR::MODELUNIT_MILLIMETER;
  if (unit == "centimeter")
    return NMR::MODELUNIT_CENTIMETER;
  if (unit == "inch")
    return NMR::MODELUNIT_INCH;
  if (unit == "foot")
    return NMR::MODELUNIT_FOOT;
  if (unit == "meter")
    return NMR::MODELUNIT_METER;
  throw std::invalid_argument("unknown 3MF unit " + unit);
}

DWORD type_code(const std::string& type) {
  if (type == "model")
    return NMR::MODELOBJECTTYPE_MODEL;
  if (type == "support")
    return NMR::MODELOBJECTTYPE_SUPPORT;
  if (type == "solidsupport")
    return NMR::MODELOBJECTTYPE_SOLIDSUPPORT;
  if (type == "surface")
    return NMR::MODELOBJECTTYPE_SURFACE;
  return NMR::MODELOBJECTTYPE_OTHER;
}

}  // namespace

struct Model3mfWriter::Impl {
  NMR::PLib3MFBase* model = nullptr;
  // Every instance lib3mf returned, released with the writer.
  std::vector<NMR::PLib3MFBase*> instances;
  std::vector<NMR::PLib3MFBase*> objects;

  ~Impl() {
    for (auto it = instances.rbegin(); it != instances.rend(); ++it)
      NMR::lib3mf_release(*it);
    if (model != nullptr)
      NMR::lib3mf_release(model);
  }
  NMR::PLib3MFBase* keep(NMR::PLib3MFBase* instance) {
    instances.push_back(instance);
    return instance;
  }
};

Model3mfWriter::Model3mfWriter(const std::string& unit) : impl_(std::make_unique<Impl>()) {
  check(NMR::lib3mf_createmodel(&impl_->model), "createmodel");
  check(NMR::lib3mf_model_setunit(impl_->model, unit_code(unit)), "setunit");
}

Model3mfWriter::~Model3mfWriter() = default;

int Model3mfWriter::add_mesh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                             const std::string& type, const std::string& name) {
  NMR::PLib3MFBase* mesh = nullptr;
  check(NMR::lib3mf_model_addmeshobject(impl_->model, &mesh), "addmeshobject");
  impl_->keep(mesh);
  std::vector<NMR::MODELMESHVERTEX> v(static_cast<std::size_t>(vertices.rows()));
  for (Eigen::Index i = 0; i < vertices.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      v[static_cast<std::size_t>(i)].m_fPosition[c] = static_cast<float>(vertices(i, c));
  std::vector<NMR::MODELMESHTRIANGLE> t(static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index i = 0; i < faces.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      t[static_cast<std::size_t>(i)].m_nIndices[c] = static_cast<DWORD>(faces(i, c));
  check(NMR::lib3mf_meshobject_setgeometry(mesh, v.data(), static_cast<DWORD>(v.size()), t.data(),
                                           static_cast<DWORD>(t.size())),
        "setgeometry");
  check(NMR::lib3mf_object_settype(mesh, type_code(type)), "settype");
  if (!name.empty())
    check(NMR::lib3mf_object_setnameutf8(mesh, name.c_str()), "setname");
  impl_->objects.push_back(mesh);
  return static_cast<int>(impl_->objects.size()) - 1;
}

void Model3mfWriter::add_beam(int object) {
  NMR::MODELMESHBEAM beam;
  beam.m_nIndices[0] = 0;
  beam.m_nIndices[1] = 1;
  beam.m_dRadius[0] = beam.m_dRadius[1] = 0.1;
  check(NMR::lib3mf_meshobject_addbeam(impl_->objects.at(static_cast<std::size_t>(object)), &beam,
                                       nullptr),
        "addbeam");
}

int Model3mfWriter::add_components(const std::vector<std::pair<int, Eigen::Affine3d>>& components) {
  NMR::PLib3MFBase* parent = nullptr;
  check(NMR::lib3mf_model_addcomponentsobject(impl_->model, &parent), "addcomponentsobject");
  impl_->keep(parent);
  for (const auto& [object, transform] : components) {
    NMR::MODELTRANSFORM m = to_model_transform(transform);
    NMR::PLib3MFBase* component = nullptr;
    check(NMR::lib3mf_componentsobject_addcomponent(
              parent, impl_->objects.at(static_cast<std::size_t>(object)), &m, &component),
          "addcomponent");
    impl_->keep(component);
  }
  impl_->objects.push_back(parent);
  return static_cast<int>(impl_->objects.size()) - 1;
}

void Model3mfWriter::add_build_item(int object, const Eigen::Affine3d& transform) {
  NMR::MODELTRANSFORM m = to_model_transform(transform);
  NMR::PLib3MFBase* item = nullptr;
  check(NMR::lib3mf_model_addbuilditem(
            impl_->model, impl_->objects.at(static_cast<std::size_t>(object)), &m, &item),
        "addbuilditem");
  impl_->keep(item);
}

void Model3mfWriter::add_build_item(int object) {
  NMR::PLib3MFBase* item = nullptr;
  check(NMR::lib3mf_model_addbuilditem(
            impl_->model, impl_->objects.at(static_cast<std::size_t>(object)), nullptr, &item),
        "addbuilditem");
  impl_->keep(item);
}

unsigned Model3mfWriter::object_id(int object) const {
  DWORD id = 0;
  check(
      NMR::lib3mf_resource_getresourceid(impl_->objects.at(static_cast<std::size_t>(object)), &id),
      "getresourceid");
  return static_cast<unsigned>(id);
}

void Model3mfWriter::write(const std::filesystem::path& path) const {
  NMR::PLib3MFBase* writer = nullptr;
  check(NMR::lib3mf_model_querywriter(impl_->model, "3mf", &writer), "querywriter");
  const LIB3MFRESULT result = NMR::lib3mf_writer_writetofileutf8(writer, path.c_str());
  NMR::lib3mf_release(writer);
  check(result, "writetofile");
}

}  // namespace bemshape::testing
