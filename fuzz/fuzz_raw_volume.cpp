// Fuzz harness: fem::read_raw_volume. The first six bytes are the dimensions NX, NY, NZ as
// little-endian 16-bit numbers (so claims far beyond the file, zero and huge products are
// tried), the rest is the file. A volume that is read must hold NX·NY·NZ flags.
#include <cstdlib>

#include "fem/binary_image.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bemshape;
  if (size < 6) return 0;
  std::array<fem::GridIndex, 3> dims{};
  for (int d = 0; d < 3; ++d) dims[d] = data[2 * d] | (fem::GridIndex(data[2 * d + 1]) << 8);
  const auto path = fuzz::input_file(data + 6, size - 6, ".raw");
  fuzz::refusal_allowed([&] {
    const fem::BinaryImage<3> volume = fem::read_raw_volume(path, dims);
    if (volume.size != dims ||
        static_cast<fem::GridIndex>(volume.solid.size()) != dims[0] * dims[1] * dims[2])
      std::abort();
  });
  return 0;
}
