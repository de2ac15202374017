#include "apps/output/png_writer.hpp"

#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "apps/output/atomic_file.hpp"
#include "core/errors.hpp"

namespace bemshape::output {
namespace {

/// 3×5 glyphs, one row of 3 bits per entry, top row first.
struct Glyph {
  char c;
  std::array<std::uint8_t, 5> rows;
};
constexpr std::array<Glyph, 15> kFont{{{'0', {7, 5, 5, 5, 7}},
                                       {'1', {2, 6, 2, 2, 7}},
                                       {'2', {7, 1, 7, 4, 7}},
                                       {'3', {7, 1, 7, 1, 7}},
                                       {'4', {5, 5, 7, 1, 1}},
                                       {'5', {7, 4, 7, 1, 7}},
                                       {'6', {7, 4, 7, 5, 7}},
                                       {'7', {7, 1, 1, 1, 1}},
                                       {'8', {7, 5, 7, 5, 7}},
                                       {'9', {7, 5, 7, 1, 7}},
                                       {'.', {0, 0, 0, 0, 2}},
                                       {'-', {0, 0, 7, 0, 0}},
                                       {'+', {0, 2, 7, 2, 0}},
                                       {'e', {0, 7, 7, 4, 7}},
                                       {' ', {0, 0, 0, 0, 0}}}};

std::string label(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

}  // namespace

RgbImage::RgbImage(int width, int height, Rgb background)
    : width_(width),
      height_(height),
      pixels_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), background) {}

void RgbImage::set(int x, int y, Rgb colour) {
  if (x >= 0 && y >= 0 && x < width_ && y < height_)
    at(x, y) = colour;
}

void RgbImage::fill_rectangle(int x0, int y0, int x1, int y1, Rgb colour) {
  for (int y = std::max(0, y0); y < std::min(height_, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(width_, x1); ++x)
      at(x, y) = colour;
}

void RgbImage::draw_line(int x0, int y0, int x1, int y1, Rgb colour) {
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int error = dx + dy;
  while (true) {
    set(x0, y0, colour);
    if (x0 == x1 && y0 == y1)
      break;
    const int e2 = 2 * error;
    if (e2 >= dy) {
      error += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      error += dx;
      y0 += sy;
    }
  }
}

void RgbImage::draw_text(int x, int y, const std::string& text, Rgb colour, int scale) {
  for (char c : text) {
    for (const auto& glyph : kFont) {
      if (glyph.c != c)
        continue;
      for (int row = 0; row < 5; ++row)
        for (int col = 0; col < 3; ++col)
          if (glyph.rows[row] & (4 >> col))
            fill_rectangle(x + col * scale, y + row * scale, x + (col + 1) * scale,
                           y + (row + 1) * scale, colour);
    }
    x += 4 * scale;
  }
}

void RgbImage::write_png(const std::filesystem::path& path) const {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width_);
  image.height = static_cast<png_uint_32>(height_);
  image.format = PNG_FORMAT_RGB;
  static_assert(sizeof(Rgb) == 3, "Rgb pixels are packed bytes");
  png_alloc_size_t bytes = 0;
  if (!png_image_write_to_memory(&image, nullptr, &bytes, 0, pixels_.data(), 0, nullptr))
    throw InputError(path.string() + ": cannot encode PNG (" + image.message + ")");
  std::vector<char> buffer(bytes);
  if (!png_image_write_to_memory(&image, buffer.data(), &bytes, 0, pixels_.data(), 0, nullptr))
    throw InputError(path.string() + ": cannot encode PNG (" + image.message + ")");
  write_file_atomically(path, std::string_view(buffer.data(), bytes));
}

RgbImage paint_scalar_field(const Eigen::Ref<const Eigen::VectorXd>& values, int nx, int ny,
                            const std::vector<char>& shown, const FieldPictureOptions& options) {
  const int k = std::max(1, options.pixels_per_cell);
  const int field_width = nx * k, height = ny * k;
  const int bar_gap = options.colour_bar ? 12 : 0, bar_width = options.colour_bar ? 16 : 0;
  const int label_width = options.colour_bar ? 4 * 2 * 9 + 8 : 0;
  RgbImage canvas(field_width + bar_gap + bar_width + label_width, std::max(height, 60),
                  {255, 255, 255});
  const double span = options.maximum - options.minimum;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const auto e = static_cast<Eigen::Index>(j) * nx + i;
      const Rgb colour = shown[static_cast<std::size_t>(e)]
                             ? viridis(span > 0 ? (values[e] - options.minimum) / span : 0.5)
                             : options.background;
      const int top = (ny - 1 - j) * k;  // y up in the field, row 0 at the top of the PNG
      canvas.fill_rectangle(i * k, top, (i + 1) * k, top + k, colour);
    }
  }
  if (options.colour_bar) {
    const int x0 = field_width + bar_gap, top = 4, bottom = canvas.height() - 4;
    for (int y = top; y < bottom; ++y) {
      const double t = 1.0 - static_cast<double>(y - top) / std::max(1, bottom - top - 1);
      canvas.fill_rectangle(x0, y, x0 + bar_width, y + 1, viridis(t));
    }
    const Rgb black{0, 0, 0};
    canvas.draw_text(x0 + bar_width + 4, top, label(options.maximum), black);
    canvas.draw_text(x0 + bar_width + 4, (top + bottom) / 2 - 5,
                     label(0.5 * (options.minimum + options.maximum)), black);
    canvas.draw_text(x0 + bar_width + 4, bottom - 10, label(options.minimum), black);
  }
  return canvas;
}

}  // namespace bemshape::output
