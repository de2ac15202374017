// Image input: PNG round trip with the y-up convention, invert, colour PNGs thresholded on
// luminance, PNG stacks, raw volumes; bad files give InputError and absurd sizes
// ResourceError before any allocation.
#include <catch2/catch.hpp>

#include <png.h>
#include <zlib.h>

#include <cstring>
#include <fstream>

#include "core/errors.hpp"
#include "fem/binary_image.hpp"

using namespace bemshape;
using namespace bemshape::fem;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "bemshape_test_binary_image";
  fs::create_directories(dir);
  return dir / name;
}

BinaryImage<2> l_shape() {
  BinaryImage<2> image;
  image.size = {5, 3};
  image.solid = {1, 1, 1, 0, 0,   // y = 0 (bottom row)
                 1, 0, 0, 0, 0,   // y = 1
                 1, 0, 0, 0, 1};  // y = 2 (top row)
  return image;
}

}  // namespace

TEST_CASE("PNG round trip keeps pixels, with y pointing up") {
  const auto path = scratch("l.png");
  write_binary_png(path, l_shape());
  const auto image = read_png_image(path);
  CHECK(image.size == l_shape().size);
  CHECK(image.solid == l_shape().solid);
  CHECK(image.at({4, 2}));  // top-right pixel
  const auto inverted = read_png_image(path, true);
  for (std::size_t i = 0; i < image.solid.size(); ++i)
    CHECK(inverted.solid[i] == !image.solid[i]);
}

TEST_CASE("colour PNG: dark pixels are solid") {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = 3;
  png.height = 1;
  png.format = PNG_FORMAT_RGB;
  const std::uint8_t rgb[] = {10, 20, 30, 250, 240, 255, 200, 30, 30};  // dark, white, red
  const auto path = scratch("rgb.png");
  REQUIRE(png_image_write_to_file(&png, path.string().c_str(), 0, rgb, 0, nullptr));
  const auto image = read_png_image(path);
  CHECK(image.solid == std::vector<std::uint8_t>{1, 0, 1});  // red has luminance ≈ 0.2
}

TEST_CASE("PNG stack is read slice by slice in name order") {
  const fs::path dir = scratch("stack");
  fs::create_directories(dir);
  auto slice = l_shape();
  write_binary_png(dir / "slice_000.png", slice);
  slice.solid.assign(slice.solid.size(), 0);
  write_binary_png(dir / "slice_001.png", slice);
  const auto volume = read_png_stack(dir);
  CHECK(volume.size == std::array<GridIndex, 3>{5, 3, 2});
  CHECK(volume.at({0, 2, 0}));
  CHECK_FALSE(volume.at({0, 2, 1}));
}

TEST_CASE("raw volume: non-zero bytes are solid, size must match the dimensions") {
  const auto path = scratch("volume.raw");
  {
    std::ofstream out(path, std::ios::binary);
    const char bytes[] = {0, 1, 0, 7, 0, 0, 0, 1};
    out.write(bytes, sizeof bytes);
  }
  const auto volume = read_raw_volume(path, {2, 2, 2});
  CHECK(volume.solid == std::vector<std::uint8_t>{0, 1, 0, 1, 0, 0, 0, 1});
  CHECK(volume.at({1, 1, 0}));
  CHECK_THROWS_AS(read_raw_volume(path, {2, 2, 3}), InputError);
  CHECK_THROWS_AS(read_raw_volume(path, {100000, 100000, 100000}), ResourceError);
}

TEST_CASE("bad image files give InputError") {
  CHECK_THROWS_AS(read_png_image(scratch("missing.png")), InputError);
  const auto path = scratch("not_a_png.png");
  std::ofstream(path) << "this is text, not an image";
  CHECK_THROWS_AS(read_png_image(path), InputError);
  CHECK_THROWS_AS(read_png_stack(scratch("no_such_folder")), InputError);
}

TEST_CASE("a PNG header claiming an absurd size is refused before allocating") {
  // A hand-made PNG: signature and an IHDR chunk claiming 60000 × 60000 pixels (3.6·10⁹,
  // within libpng's own limits but above kMaxImagePixels), correct CRCs, no pixel data.
  std::vector<unsigned char> bytes = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  const auto be32 = [](std::uint32_t v) {
    return std::array<unsigned char, 4>{
        static_cast<unsigned char>(v >> 24), static_cast<unsigned char>(v >> 16),
        static_cast<unsigned char>(v >> 8), static_cast<unsigned char>(v)};
  };
  const auto append_chunk = [&](const char* type, const std::vector<unsigned char>& data) {
    std::vector<unsigned char> chunk(type, type + 4);
    chunk.insert(chunk.end(), data.begin(), data.end());
    for (auto b : be32(static_cast<std::uint32_t>(data.size())))
      bytes.push_back(b);
    bytes.insert(bytes.end(), chunk.begin(), chunk.end());
    for (auto b : be32(static_cast<std::uint32_t>(
             crc32(0, chunk.data(), static_cast<unsigned>(chunk.size())))))
      bytes.push_back(b);
  };
  std::vector<unsigned char> header;
  for (auto b : be32(60000))
    header.push_back(b);
  for (auto b : be32(60000))
    header.push_back(b);
  header.insert(header.end(), {8, 0, 0, 0, 0});  // 8-bit grey, deflate, no interlace
  append_chunk("IHDR", header);
  append_chunk("IDAT", {});
  append_chunk("IEND", {});
  const auto path = scratch("huge.png");
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  CHECK_THROWS_AS(read_png_image(path), ResourceError);
}

TEST_CASE("a pixel check sees the count before the pixels are allocated, and may refuse") {
  struct Refused {
    GridIndex pixels;
  };
  std::vector<GridIndex> seen;
  const PixelCheck record = [&seen](GridIndex pixels) { seen.push_back(pixels); };
  const PixelCheck refuse = [](GridIndex pixels) { throw Refused{pixels}; };

  const auto png = scratch("checked.png");
  write_binary_png(png, l_shape());
  CHECK(read_png_image(png, false, record).solid == l_shape().solid);
  CHECK(seen == std::vector<GridIndex>{15});
  try {
    read_png_image(png, false, refuse);
    FAIL("the check did not run");
  } catch (const Refused& r) {
    CHECK(r.pixels == 15);
  }

  // A stack: the first slice on its own (decoded before the volume's size is known), then
  // the volume.
  const fs::path dir = scratch("checked_stack");
  fs::create_directories(dir);
  for (const char* name : {"a.png", "b.png", "c.png"})
    write_binary_png(dir / name, l_shape());
  seen.clear();
  CHECK(read_png_stack(dir, false, record).num_pixels() == 45);
  CHECK(seen == std::vector<GridIndex>{15, 45});

  const auto raw = scratch("checked.raw");
  {
    std::ofstream out(raw, std::ios::binary);
    out << std::string(24, '\1');
  }
  seen.clear();
  CHECK(read_raw_volume(raw, {2, 3, 4}, false, record).num_pixels() == 24);
  CHECK(seen == std::vector<GridIndex>{24});
  // The file must match --dims before the budget is asked.
  CHECK_THROWS_AS(read_raw_volume(raw, {2, 3, 5}, false, refuse), InputError);
  CHECK_THROWS_AS(read_raw_volume(raw, {2, 3, 4}, false, refuse), Refused);
}
