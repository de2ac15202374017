#pragma once
// PNG pictures of 2-D fields, like the paper's figures: an RGB canvas with simple drawing
// (filled rectangles, lines, a built-in 3×5 pixel font for numbers), a scalar field painted
// with the viridis map (colour_map.hpp) next to a labelled colour bar, and atomic PNG output
// (8-bit RGB, libpng).

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "apps/output/colour_map.hpp"

namespace bemshape::output {

/// Pixels row-major with row 0 at the TOP (PNG order).
class RgbImage {
 public:
  RgbImage(int width, int height, Rgb background = {255, 255, 255});
  int width() const { return width_; }
  int height() const { return height_; }
  Rgb& at(int x, int y) { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  const Rgb& at(int x, int y) const { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  /// Sets a pixel if it lies on the canvas.
  void set(int x, int y, Rgb colour);
  void fill_rectangle(int x0, int y0, int x1, int y1, Rgb colour);  ///< [x0, x1) × [y0, y1)
  void draw_line(int x0, int y0, int x1, int y1, Rgb colour);       ///< Bresenham
  /// Digits, '.', '-', '+', 'e' in a 3×5 font scaled by `scale`; top-left corner at (x, y).
  void draw_text(int x, int y, const std::string& text, Rgb colour, int scale = 2);
  /// Writes an 8-bit RGB PNG atomically; throws InputError on failure.
  void write_png(const std::filesystem::path& path) const;

 private:
  int width_, height_;
  std::vector<Rgb> pixels_;
};

struct FieldPictureOptions {
  double minimum = 0.0, maximum = 1.0;  ///< colour range; values are clamped to it
  int pixels_per_cell = 1;
  Rgb background{255, 255, 255};  ///< where `shown` is 0 (e.g. outside the solid)
  bool colour_bar = true;         ///< vertical bar with min/mid/max labels on the right
};

/// Paints `values` (#cells, x fastest, y UP) of an nx×ny grid; cells with shown[e] == 0
/// get the background colour. Returns the canvas (callers may draw on it, then write it).
RgbImage paint_scalar_field(const Eigen::Ref<const Eigen::VectorXd>& values, int nx, int ny,
                            const std::vector<char>& shown, const FieldPictureOptions& options);

}  // namespace bemshape::output
