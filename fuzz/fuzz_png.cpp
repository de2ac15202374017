// Fuzz harness: bytes as a .png file through fem::read_png_image (libpng under bemshape's
// error handling and pixel-count guard), in both polarities. A decoded image must have as
// many flags as pixels.
#include <cstdlib>

#include "fem/binary_image.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bemshape;
  const auto path = fuzz::input_file(data, size, ".png");
  for (const bool invert : {false, true})
    fuzz::refusal_allowed([&] {
      const fem::BinaryImage<2> image = fem::read_png_image(path, invert);
      if (static_cast<fem::GridIndex>(image.solid.size()) != image.num_pixels()) std::abort();
    });
  return 0;
}
