#pragma once
// The memory guards of the pipeline, in one place: each refuses a stage that would not fit
// before it allocates, with core/memory.hpp's ResourceError naming the budget (the machine's
// available memory, `ulimit -v`, --max-memory) and a setting that fits.
//
//   the dense BEM system:  32·N² bytes for N solver faces (bem::dense_solver_memory_bytes);
//                          the refusal names a --max-edge whose mesh fits;
//   the H-matrix path:     its own estimate and guard, inside bem::solve_transmission_hmatrix
//                          (it needs the exterior operator's pair count, which only the
//                          solver's cluster tree gives; it also shortens the GMRES restart
//                          and picks the far field's form to fit);
//   the voxel FEM grid:    fem::estimated_run_bytes<D> of the planned grid, before anything
//                          per cell is allocated; the refusal names a --cell that fits;
//   an input image:        its pixels from the header, before any is decoded;
//   held allocations:      what one stage keeps through a later one comes off the later
//                          one's --max-memory (remaining_memory_limit).

#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "core/solver_memory_refusal.hpp"
#include "features/feature_parameters.hpp"
#include "fem/binary_image.hpp"
#include "fem/characteristic_function.hpp"

namespace bemshape::analysis {

/// --max-memory for a stage that runs while `held_bytes` of an earlier one stay allocated:
/// the rest of max_memory_bytes, at least 1 byte; 0 (no limit given) stays 0.
std::uint64_t remaining_memory_limit(std::uint64_t max_memory_bytes, std::uint64_t held_bytes);

/// What the refusal of a dense BEM system names.
struct DenseSystemRefusal {
  std::string source;               ///< the input, named first
  Eigen::Index solver_faces = 0;    ///< N
  double max_edge = 0.0;            ///< the solver mesh's target edge [model units]
  std::string max_edge_rule;        ///< where max_edge came from
  double flat_wall_max_edge = 0.0;  ///< 2.5·a·h0 [model units]: flat walls stay accurate up to it
  std::uint64_t max_memory_bytes = 0;  ///< --max-memory; 0: the machine's memory only
};

/// Throws refuse_dense_system's error if the dense system of refusal.solver_faces faces
/// exceeds the budget (memory_budget_bytes(max_memory_bytes)); nothing if it fits or no
/// budget is known.
void require_dense_system_fits(const DenseSystemRefusal& refusal);

/// The one-line refusal of a dense system that does not fit in `budget_bytes`: how many
/// faces, how much memory, and a --max-edge that fits (faces scale like 1/edge², memory like
/// faces²; 10 % below the budget, since the remesher's face count for an edge varies by a few
/// percent).
[[noreturn]] void refuse_dense_system(const DenseSystemRefusal& refusal,
                                      std::uint64_t budget_bytes);

/// A uniform solver mesh of target edge e (geometry::refine_to_edge_length, edges up to 1.3·e)
/// over a surface of area A has about A/(kRemeshedFaceAreaRatio·e²) faces: its triangles are
/// smaller than the equilateral one of side e (√3/4 ≈ 0.433). Measured on the remesher's
/// output (docs/usage.md, "Solver size"); a first guess only: the solver's
/// estimate on the remeshed mesh decides.
inline constexpr double kRemeshedFaceAreaRatio = 0.29;

/// The share of the budget a mesh chosen to fit aims at: the estimate on the remeshed mesh,
/// whose face count the prediction misses by a few per cent, must still fit.
inline constexpr double kFitMargin = 0.85;

/// The solver faces to aim at so that a refused solve fits kFitMargin of the budget, by the
/// estimate of the solver that takes them: above `dense_up_to` faces the hierarchical-matrix
/// one (the refused mesh's estimate beyond what the process holds, scaled like N), at or
/// below it the dense path's bound bem::dense_solver_peak_bytes (inverted exactly). 0 where
/// nothing fits.
double fitting_solver_faces(const SolverMemoryRefusal& refused, long dense_up_to);

/// The target edge of a uniform solver mesh of about `faces` faces over `area`.
double uniform_mesh_edge_for_faces(double area, double faces);

/// `edge` rounded up to the 3 significant digits a message prints it with, so that the
/// --max-edge a refusal names is the edge it confirmed.
double fitting_edge_text_value(double edge);

/// What accuracy to expect at a uniform --max-edge `edge`, from the element size rules
/// (docs/usage.md, "Element size"): surface values within about 1 % up to 1.5·a·h0, flat
/// walls accurate up to 2.5·a·h0, beyond that not validated.
std::string fitting_mesh_accuracy(double edge, double h0, double a);

/// What a voxel run's memory check needs to know about its request.
struct VoxelMemoryBudget {
  std::string input;                   ///< the input file, named in the message
  double cell = 0.0;                   ///< --cell [model units]
  bool h0_given = false;               ///< --h0 given (else h0 = kDefaultH0Cells cells)
  std::uint64_t max_memory_bytes = 0;  ///< --max-memory; 0: the machine's memory only
};

/// Refuses a planned grid whose FEM run (fem::estimated_run_bytes<D>) exceeds the budget.
/// The message suggests the smallest --cell, in steps of 10 %, whose grid fits. Without --h0,
/// h0 follows the cell (kDefaultH0Cells cells) and so does the margin of 1.2·h0 around the
/// part, so below a certain budget no cell size fits; the suggestion then keeps this run's
/// h0 (--cell X --h0 H).
template <int D>
fem::GridCheck<D> voxel_grid_memory_check(const VoxelMemoryBudget& budget,
                                          const features::FeatureParameters& parameters);

/// Bytes held per pixel while an image is read: the decoded grey levels and the solid flags
/// of a PNG (2), the solid flags of a volume (1; a slice's grey levels are transient).
template <int D>
inline constexpr double kImageReadBytesPerPixel = D == 2 ? 2.0 : 1.0;

/// Refuses an image (its pixel count read from the header or --dims) whose pixels would
/// not fit the budget, suggesting a downsampled image or a larger --max-memory.
template <int D>
fem::PixelCheck image_memory_check(const VoxelMemoryBudget& budget);

}  // namespace bemshape::analysis
