#include "apps/output/ply_writer.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

#include "apps/output/atomic_file.hpp"
#include "apps/output/colour_map.hpp"
#include "core/errors.hpp"

namespace bemshape::output {

static_assert(std::endian::native == std::endian::little,
              "the PLY files declare binary_little_endian and are written from memory");

void write_ply(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices,
               const Eigen::MatrixX3i& faces, const Eigen::Ref<const Eigen::VectorXd>& field,
               const PlyColouring& colouring) {
  if (field.size() != vertices.rows())
    throw InternalError("write_ply: field has " + std::to_string(field.size()) + " values for " +
                        std::to_string(vertices.rows()) + " vertices");
  const bool defects = !colouring.defect.empty();
  if (defects && colouring.defect.size() != static_cast<std::size_t>(vertices.rows()))
    throw InternalError("write_ply: " + std::to_string(colouring.defect.size()) +
                        " defect flags for " + std::to_string(vertices.rows()) + " vertices");
  if (colouring.field_name == "quality")
    throw InternalError("write_ply: the field may not be named 'quality', the name of its copy");
  std::string header = "ply\nformat binary_little_endian 1.0\n";
  if (!colouring.comment.empty())
    header += "comment " + colouring.comment + '\n';
  header += "element vertex " + std::to_string(vertices.rows()) + '\n';
  header += "property float x\nproperty float y\nproperty float z\n";
  header += "property float " + colouring.field_name + "\nproperty float quality\n";
  header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (defects)
    header += "property uchar defect\n";
  header += "element face " + std::to_string(faces.rows()) + '\n';
  header += "property list uchar int vertex_indices\nend_header\n";

  const double range = colouring.colour_maximum - colouring.colour_minimum;
  std::vector<char> payload;
  payload.reserve(static_cast<std::size_t>(vertices.rows() * (defects ? 24 : 23) + faces.rows() * 13));
  const auto put = [&payload](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const char*>(data);
    payload.insert(payload.end(), p, p + bytes);
  };
  for (Eigen::Index v = 0; v < vertices.rows(); ++v) {
    const float values[5] = {static_cast<float>(vertices(v, 0)), static_cast<float>(vertices(v, 1)),
                             static_cast<float>(vertices(v, 2)), static_cast<float>(field(v)),
                             static_cast<float>(field(v))};
    put(values, sizeof values);
    const double t = range > 0.0 ? (field(v) - colouring.colour_minimum) / range : 0.5;
    const bool defect = defects && colouring.defect[static_cast<std::size_t>(v)] != 0;
    const Rgb c = defect ? kDefectColour : viridis(t);
    const std::uint8_t rgb[3] = {c.r, c.g, c.b};
    put(rgb, sizeof rgb);
    if (defects) {
      const std::uint8_t flag = defect ? 1 : 0;
      put(&flag, 1);
    }
  }
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const std::uint8_t corners = 3;
    put(&corners, 1);
    const std::int32_t indices[3] = {faces(f, 0), faces(f, 1), faces(f, 2)};
    put(indices, sizeof indices);
  }
  AtomicFileWriter writer(path);
  writer.write(header);
  writer.write(payload.data(), payload.size());
  writer.commit();
}

}  // namespace bemshape::output
