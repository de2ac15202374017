#pragma once
// The units check of a thickness run: a length the user gave (h0, the minimum wall) that the
// part's own size says cannot be meant in the file's units — a file in metres checked against
// a limit in millimetres reads thinner than the limit everywhere, or a limit in metres on a
// file in millimetres passes every part (docs/usage.md, "Units check"). One line naming the
// likely mix-up, for the printed report, the JSON report, the HTML page and the Python dict.
//
// A length L [file units] is implausible when
//   L > kSideMultiple·(the part's smallest bounding-box side), or L > kWallMultiple·(2·V/A)
//                                                                          (too large), or
//   L < (2·V/A)/kWallMultiple², for a limit only                            (too small),
// 2·V/A being the wall of a plate and about the nominal wall of a thin-walled part
// (analysis::part_h0).

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geometry/surface_mesh.hpp"

namespace bemshape::apps {

/// How far from the part's typical wall 2·V/A a length may be. A limit ten times the wall
/// flags the whole part, and a limit a hundredth of it (kWallMultiple²) passes any part whose
/// walls are near their nominal: neither is a check anyone means, while the unit mix-ups are
/// factors of 25.4 and more, so they are caught with room to spare.
inline constexpr double kWallMultiple = 10.0;

/// How far above the part's smallest bounding-box side a length may be. A plate read at its
/// own thickness (h0 = t, the recommended h0) or checked at a limit a little above it is
/// meant; its side, computed from the file's coordinates, can be a rounding below t. Twice the
/// side is no wall anyone checks, while the unit mix-ups are factors of 10 and more.
inline constexpr double kSideMultiple = 2.0;

/// The part's size as the check reads it [file units].
struct PartSize {
  Eigen::Vector3d sides = Eigen::Vector3d::Zero();  ///< bounding-box sides
  double typical_wall = 0.0;  ///< 2·V/A; 0 when the volume is not positive
};

/// The sides of `mesh`'s bounding box and 2·volume/area.
PartSize part_size(const geometry::SurfaceMesh& mesh, double volume, double area);

/// A length as the user gave it, named as the front end spells it ("--min-thickness",
/// "min_thickness").
struct GivenLength {
  std::string name;
  double value = 0.0;  ///< [file units]
  bool limit = false;  ///< a check's limit (a false PASS if too small), not h0
};

/// The first implausible length of `lengths` as one line ("units: … "), naming the likely
/// mix-up (metres and millimetres, inches and millimetres, …: the one that makes the length
/// plausible and nearest the part's typical wall) and ending with `silencer` (how to turn the
/// check off); nothing when every length is plausible.
std::optional<std::string> units_warning(const PartSize& part,
                                         const std::vector<GivenLength>& lengths,
                                         const std::string& silencer);

/// What a report says about the check: whether it ran and its warning.
struct UnitsCheck {
  bool enabled = false;
  std::optional<std::string> warning;
};

}  // namespace bemshape::apps
