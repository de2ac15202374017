#pragma once
// Binary images and volumes: the voxel solver's image input.
//
//   size:  pixels (voxels) along x, y (, z)
//   solid: Π size flags, 1 = solid (χ = 1); x fastest, then y, then z
//
// Orientation: y points UP, as in the paper's figures and in model coordinates, so PNG row 0
// (the top row of the picture) is stored as y = height − 1. PNG slices of a volume are
// z = 0, 1, … in the lexicographic order of their file names.
//
// Conventions: in a PNG, dark pixels (grey value < 50% after compositing any alpha onto
// white) are solid, the paper's "black domain"; `invert` makes light pixels solid. In a raw
// volume every non-zero byte is solid (`invert`: every zero byte).

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "fem/voxel_grid.hpp"

namespace bemshape::fem {

template <int D>
struct BinaryImage {
  std::array<GridIndex, D> size{};
  std::vector<std::uint8_t> solid;

  GridIndex num_pixels() const {
    GridIndex n = 1;
    for (int d = 0; d < D; ++d)
      n *= size[d];
    return n;
  }
  bool at(const std::array<GridIndex, D>& p) const {
    GridIndex index = 0;
    for (int d = D - 1; d >= 0; --d)
      index = index * size[d] + p[d];
    return solid[static_cast<std::size_t>(index)] != 0;
  }
};

/// Largest image or volume read (pixels): 2^31 flags are 2 GB before any solver memory, so
/// a header claiming more is refused before anything is allocated.
inline constexpr GridIndex kMaxImagePixels = GridIndex{1} << 31;

/// Sees the pixel (voxel) count of an image once it is known from the header or the
/// dimensions and before the pixels are allocated; may throw to refuse the image
/// (analysis/memory_budget.hpp checks --max-memory with it).
using PixelCheck = std::function<void(GridIndex pixels)>;

/// Reads a PNG (any colour type or bit depth). Throws InputError if the file is missing or
/// not a readable PNG, ResourceError if it has more than kMaxImagePixels pixels; `check`,
/// when set, sees the pixel count first.
BinaryImage<2> read_png_image(const std::filesystem::path& path, bool invert = false,
                              const PixelCheck& check = {});

/// Reads a folder of equally sized PNG slices (*.png, sorted by name) as a volume; `check`,
/// when set, sees the voxel count (first slice's size × slices) before the volume is
/// allocated.
BinaryImage<3> read_png_stack(const std::filesystem::path& folder, bool invert = false,
                              const PixelCheck& check = {});

/// Reads NX·NY·NZ bytes (x fastest) as a volume; the file size must match exactly. `check`,
/// when set, sees NX·NY·NZ before the volume is allocated.
BinaryImage<3> read_raw_volume(const std::filesystem::path& path,
                               const std::array<GridIndex, 3>& dims, bool invert = false,
                               const PixelCheck& check = {});

/// Writes a 2-D binary image as an 8-bit grey PNG (solid black, void white), the inverse of
/// read_png_image (used to round-trip generated test images).
void write_binary_png(const std::filesystem::path& path, const BinaryImage<2>& image);

}  // namespace bemshape::fem
