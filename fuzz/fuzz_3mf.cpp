// Fuzz harness: bytes as a .3mf file through geometry::read_triangle_soup (lib3mf parses the
// ZIP package and its XML), then validation and repair (fuzz/mesh_file_harness.hpp). Seeds:
// tests/data files of this format.
#include "fuzz/mesh_file_harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return bemshape::fuzz::run_mesh_file(data, size, ".3mf");
}
