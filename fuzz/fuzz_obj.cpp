// Fuzz harness: bytes as a .obj file through geometry::read_triangle_soup, then validation
// and repair (fuzz/mesh_file_harness.hpp). Seeds: tests/data files of this format.
#include "fuzz/mesh_file_harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return bemshape::fuzz::run_mesh_file(data, size, ".obj");
}
