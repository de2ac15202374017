#include "apps/output/stl_writer.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

#include <Eigen/Geometry>

#include "apps/output/atomic_file.hpp"

namespace bemshape::output {

static_assert(std::endian::native == std::endian::little,
              "binary STL is little-endian and is written from memory");

void write_binary_stl(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices,
                      const Eigen::MatrixX3i& faces) {
  std::vector<char> bytes(84 + 50 * static_cast<std::size_t>(faces.rows()), 0);
  const char title[] = "binary STL written by bemshape";
  std::copy(title, title + sizeof title - 1, bytes.begin());
  const auto count = static_cast<std::uint32_t>(faces.rows());
  std::memcpy(bytes.data() + 80, &count, 4);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0)), b = vertices.row(faces(f, 1)),
                          c = vertices.row(faces(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    float record[12];
    for (int k = 0; k < 3; ++k) {
      record[k] = static_cast<float>(n(k));
      record[3 + k] = static_cast<float>(a(k));
      record[6 + k] = static_cast<float>(b(k));
      record[9 + k] = static_cast<float>(c(k));
    }
    std::memcpy(bytes.data() + 84 + 50 * f, record, sizeof record);
  }
  write_file_atomically(path, std::string_view(bytes.data(), bytes.size()));
}

}  // namespace bemshape::output
