#pragma once
// How finely the voxel FEM must resolve the PDE: the rules `bemshape fem` and the comparison
// with the BEM (analysis/compare_with_fem.hpp) share. κ = 2/(a·h0) is the decay rate of s
// outside the solid; its boundary layer, of width 1/κ, is what the grid must resolve.

namespace bemshape::analysis {

/// Default h0 in cells: κ·cell = 2·cell/(a·h0) = 0.5 at a = 0.2, the resolution at which the
/// thickness error is about 1% (docs/validation.md).
inline constexpr double kDefaultH0Cells = 20.0;
/// κ·cell above which the exterior boundary layer is under-resolved (errors of several %).
inline constexpr double kMaxResolvedKappaCell = 0.5;

}  // namespace bemshape::analysis
