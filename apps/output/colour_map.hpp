#pragma once
// A perceptually uniform sequential colour map approximating matplotlib's "viridis"
// (dark blue → green → yellow): piecewise-linear interpolation between 9 anchor colours
// sampled from the published map at t = 0, 1/8, …, 1. Lightness increases monotonically, so
// the maps read correctly in grey scale and for colour-blind readers.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace bemshape::output {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

/// The colour of faces and vertices near a defect region (a surface that crosses itself,
/// measured as given): magenta, which viridis never reaches, so it reads as "not the map".
inline constexpr Rgb kDefectColour{230, 0, 180};

/// Colour of t ∈ [0, 1] (clamped; NaN gives the lowest colour).
inline Rgb viridis(double t) {
  static constexpr std::array<std::array<double, 3>, 9> kAnchors{{{68, 1, 84},
                                                                  {71, 44, 122},
                                                                  {59, 81, 139},
                                                                  {44, 113, 142},
                                                                  {33, 144, 141},
                                                                  {39, 173, 129},
                                                                  {92, 200, 99},
                                                                  {170, 220, 50},
                                                                  {253, 231, 37}}};
  if (!(t > 0.0))
    t = 0.0;
  t = std::min(t, 1.0);
  const double u = t * (kAnchors.size() - 1);
  const auto i = std::min<std::size_t>(static_cast<std::size_t>(u), kAnchors.size() - 2);
  const double w = u - static_cast<double>(i);
  Rgb c;
  const auto mix = [&](int k) {
    return static_cast<std::uint8_t>(
        std::lround((1.0 - w) * kAnchors[i][k] + w * kAnchors[i + 1][k]));
  };
  c.r = mix(0);
  c.g = mix(1);
  c.b = mix(2);
  return c;
}

}  // namespace bemshape::output
