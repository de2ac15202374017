#pragma once
// Test helper: writes 3MF files with lib3mf's own writer (lib3mf 1.x, the library bemshape
// reads 3MF with), so the reader tests start from files a 3MF producer wrote rather than
// from XML typed by hand.
//
// Note on precision: lib3mf 1.8.1 stores vertices and transforms as float32 and its writer
// prints coordinates with six decimals ("%f"), so a coordinate comes back within
// max(float32 rounding, 5e-7) of what was written.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace bemshape::testing {

class Model3mfWriter {
 public:
  /// unit: the model's `unit` attribute ("micron", "millimeter", "centimeter", "inch",
  /// "foot", "meter").
  explicit Model3mfWriter(const std::string& unit = "millimeter");
  ~Model3mfWriter();
  Model3mfWriter(const Model3mfWriter&) = delete;
  Model3mfWriter& operator=(const Model3mfWriter&) = delete;

  /// Adds a mesh object (type "model", "support", "solidsupport", "surface" or "other");
  /// returns its index for components and build items (not its 3MF id).
  int add_mesh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
               const std::string& type = "model", const std::string& name = "");
  /// Adds beams between vertices 0-1 of mesh `object` (the beam lattice extension).
  void add_beam(int object);
  /// Adds a components object placing each (object, transform); returns its index.
  int add_components(const std::vector<std::pair<int, Eigen::Affine3d>>& components);
  /// Adds a build item placing `object` (with a transform, or without one).
  void add_build_item(int object, const Eigen::Affine3d& transform);
  void add_build_item(int object);
  /// 3MF id of the object with this index.
  unsigned object_id(int object) const;

  void write(const std::filesystem::path& path) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bemshape::testing
