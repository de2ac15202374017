#include "fem/binary_image.hpp"

#include <png.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <string>

#include "core/errors.hpp"

namespace bemshape::fem {
namespace {

/// Grey level (0–255, after compositing onto white) below which a pixel is dark = solid.
constexpr int kGreyThreshold = 128;

struct PngPixels {
  GridIndex width = 0, height = 0;
  std::vector<std::uint8_t> grey;  // row 0 = top row
};

PngPixels read_grey_png(const std::filesystem::path& path, const PixelCheck& check) {
  const std::string name = path.string();
  if (!std::filesystem::is_regular_file(path))
    throw InputError(name + ": no such file; give the path of a PNG image");
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, name.c_str()))
    throw InputError(name + ": not a readable PNG (" + image.message +
                     "); export the image as PNG");
  const GridIndex width = image.width, height = image.height;
  if (width * height > kMaxImagePixels) {
    png_image_free(&image);
    throw ResourceError(name + ": the PNG header claims " + std::to_string(width) + "×" +
                        std::to_string(height) + " pixels, more than the limit of " +
                        std::to_string(kMaxImagePixels) + "; downsample the image");
  }
  if (check) {
    try {
      check(width * height);
    } catch (...) {
      png_image_free(&image);
      throw;
    }
  }
  image.format = PNG_FORMAT_GRAY;  // libpng composites alpha onto the background below
  PngPixels pixels;
  pixels.width = width;
  pixels.height = height;
  pixels.grey.resize(static_cast<std::size_t>(width * height));
  png_color background{255, 255, 255};
  if (!png_image_finish_read(&image, &background, pixels.grey.data(), 0, nullptr)) {
    const std::string message = image.message;
    png_image_free(&image);
    throw InputError(name + ": the PNG data are damaged (" + message + ")");
  }
  return pixels;
}

}  // namespace

BinaryImage<2> read_png_image(const std::filesystem::path& path, bool invert,
                              const PixelCheck& check) {
  const PngPixels pixels = read_grey_png(path, check);
  BinaryImage<2> image;
  image.size = {pixels.width, pixels.height};
  image.solid.resize(pixels.grey.size());
  for (GridIndex row = 0; row < pixels.height; ++row) {
    const GridIndex y = pixels.height - 1 - row;
    for (GridIndex x = 0; x < pixels.width; ++x) {
      const bool dark =
          pixels.grey[static_cast<std::size_t>(row * pixels.width + x)] < kGreyThreshold;
      image.solid[static_cast<std::size_t>(y * pixels.width + x)] = dark != invert;
    }
  }
  return image;
}

BinaryImage<3> read_png_stack(const std::filesystem::path& folder, bool invert,
                              const PixelCheck& check) {
  if (!std::filesystem::is_directory(folder))
    throw InputError(folder.string() + ": not a folder; give a folder of PNG slices");
  std::vector<std::filesystem::path> slices;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    auto ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (entry.is_regular_file() && ext == ".png")
      slices.push_back(entry.path());
  }
  if (slices.empty())
    throw InputError(folder.string() + ": contains no .png slices");
  std::sort(slices.begin(), slices.end());
  BinaryImage<3> volume;
  for (std::size_t z = 0; z < slices.size(); ++z) {
    // The first slice is checked on its own too: it is decoded before the volume's size
    // is known.
    const BinaryImage<2> slice = read_png_image(slices[z], invert, z == 0 ? check : PixelCheck{});
    if (z == 0) {
      volume.size = {slice.size[0], slice.size[1], static_cast<GridIndex>(slices.size())};
      if (volume.num_pixels() > kMaxImagePixels)
        throw ResourceError(folder.string() + ": " + std::to_string(slices.size()) + " slices of " +
                            std::to_string(slice.size[0]) + "×" + std::to_string(slice.size[1]) +
                            " exceed the limit of " + std::to_string(kMaxImagePixels) +
                            " voxels; downsample the slices");
      if (check)
        check(volume.num_pixels());
      volume.solid.reserve(static_cast<std::size_t>(volume.num_pixels()));
    } else if (slice.size[0] != volume.size[0] || slice.size[1] != volume.size[1]) {
      throw InputError(slices[z].string() + ": slice is " + std::to_string(slice.size[0]) + "×" +
                       std::to_string(slice.size[1]) + " but " + slices[0].filename().string() +
                       " is " + std::to_string(volume.size[0]) + "×" +
                       std::to_string(volume.size[1]) + "; all slices must have the same size");
    }
    volume.solid.insert(volume.solid.end(), slice.solid.begin(), slice.solid.end());
  }
  return volume;
}

BinaryImage<3> read_raw_volume(const std::filesystem::path& path,
                               const std::array<GridIndex, 3>& dims, bool invert,
                               const PixelCheck& check) {
  const std::string name = path.string();
  for (GridIndex n : dims)
    if (n < 1)
      throw InputError(name + ": volume dimensions must be positive (--dims NX,NY,NZ)");
  const double total =
      static_cast<double>(dims[0]) * static_cast<double>(dims[1]) * static_cast<double>(dims[2]);
  if (total > static_cast<double>(kMaxImagePixels))
    throw ResourceError(name + ": dimensions " + std::to_string(dims[0]) + "," +
                        std::to_string(dims[1]) + "," + std::to_string(dims[2]) +
                        " exceed the limit of " + std::to_string(kMaxImagePixels) + " voxels");
  if (!std::filesystem::is_regular_file(path))
    throw InputError(name + ": no such file; give the path of a raw byte volume");
  const auto bytes = static_cast<GridIndex>(std::filesystem::file_size(path));
  const auto expected = dims[0] * dims[1] * dims[2];
  if (bytes != expected)
    throw InputError(name + ": has " + std::to_string(bytes) + " bytes but --dims " +
                     std::to_string(dims[0]) + "," + std::to_string(dims[1]) + "," +
                     std::to_string(dims[2]) + " needs " + std::to_string(expected) +
                     " (one byte per voxel, x fastest); check the dimensions");
  if (check)
    check(expected);
  BinaryImage<3> volume;
  volume.size = dims;
  volume.solid.resize(static_cast<std::size_t>(expected));
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(volume.solid.data()),
               static_cast<std::streamsize>(expected)))
    throw InputError(name + ": could not read " + std::to_string(expected) + " bytes");
  for (auto& v : volume.solid)
    v = (v != 0) != invert;
  return volume;
}

void write_binary_png(const std::filesystem::path& path, const BinaryImage<2>& image) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.size[0]);
  png.height = static_cast<png_uint_32>(image.size[1]);
  png.format = PNG_FORMAT_GRAY;
  std::vector<std::uint8_t> grey(image.solid.size());
  for (GridIndex y = 0; y < image.size[1]; ++y)
    for (GridIndex x = 0; x < image.size[0]; ++x)
      grey[static_cast<std::size_t>((image.size[1] - 1 - y) * image.size[0] + x)] =
          image.solid[static_cast<std::size_t>(y * image.size[0] + x)] ? 0 : 255;
  if (!png_image_write_to_file(&png, path.string().c_str(), 0, grey.data(), 0, nullptr))
    throw InputError(path.string() + ": could not write PNG (" + png.message + ")");
}

}  // namespace bemshape::fem
