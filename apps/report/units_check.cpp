#include "apps/report/units_check.hpp"

#include <cmath>
#include <limits>

#include "core/number_text.hpp"

namespace bemshape::apps {
namespace {

/// A unit mix-up: the file in one unit, the length written in another; `length_unit` in file
/// units is `factor`.
struct MixUp {
  const char* file_unit;
  const char* length_unit;
  const char* length_symbol;
  const char* file_symbol;
  double factor;
};

constexpr MixUp kMixUps[] = {
    {"metres", "millimetres", "mm", "m", 1e-3},
    {"inches", "millimetres", "mm", "in", 1.0 / 25.4},
    {"metres", "inches", "in", "m", 0.0254},
    {"centimetres", "millimetres", "mm", "cm", 0.1},
    {"millimetres", "metres", "m", "mm", 1e3},
    {"millimetres", "inches", "in", "mm", 25.4},
};

enum class Verdict { plausible, too_large, too_small };

Verdict judge(const PartSize& part, double value, bool limit) {
  const double smallest_side = part.sides.minCoeff();
  const double wall = part.typical_wall;
  if (value > kSideMultiple * smallest_side || (wall > 0.0 && value > kWallMultiple * wall))
    return Verdict::too_large;
  if (limit && wall > 0.0 && value < wall / (kWallMultiple * kWallMultiple))
    return Verdict::too_small;
  return Verdict::plausible;
}

std::string size_text(const PartSize& part) {
  std::string text = number_text(part.sides.x(), 3) + " x " + number_text(part.sides.y(), 3) +
                     " x " + number_text(part.sides.z(), 3);
  if (part.typical_wall > 0.0)
    text += ", typical wall 2*V/A " + number_text(part.typical_wall, 3);
  return text;
}

}  // namespace

PartSize part_size(const geometry::SurfaceMesh& mesh, double volume, double area) {
  PartSize size;
  size.sides = mesh.bounding_box().extent();
  size.typical_wall = volume > 0.0 && area > 0.0 ? 2.0 * volume / area : 0.0;
  return size;
}

std::optional<std::string> units_warning(const PartSize& part,
                                         const std::vector<GivenLength>& lengths,
                                         const std::string& silencer) {
  for (const GivenLength& length : lengths) {
    const Verdict verdict = judge(part, length.value, length.limit);
    if (verdict == Verdict::plausible)
      continue;
    const std::string value = number_text(length.value, 6);
    std::string line = "units: " + length.name + " " + value + " is " +
                       (verdict == Verdict::too_large ? "larger than the part allows"
                                                      : "far below any wall of the part") +
                       " (" + size_text(part) + ")";
    // The mix-up under which the length is plausible, nearest the typical wall.
    const MixUp* best = nullptr;
    double best_distance = std::numeric_limits<double>::infinity();
    for (const MixUp& m : kMixUps) {
      const double meant = length.value * m.factor;
      if (judge(part, meant, length.limit) != Verdict::plausible)
        continue;
      const double distance =
          part.typical_wall > 0.0 ? std::abs(std::log(meant / part.typical_wall)) : 0.0;
      if (distance < best_distance) {
        best = &m;
        best_distance = distance;
      }
    }
    if (best != nullptr)
      line += ": is the file in " + std::string(best->file_unit) + " and " + value +
              " meant in " + best->length_unit + "? " + value + " " + best->length_symbol +
              " is " + number_text(length.value * best->factor, 6) + " " + best->file_symbol;
    else
      line += ": check the units of the file and of " + length.name;
    return line + " (" + silencer + " silences this)";
  }
  return std::nullopt;
}

}  // namespace bemshape::apps
