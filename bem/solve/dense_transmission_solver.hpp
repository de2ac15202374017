#pragma once
// Reference solver of the shape-feature transmission problem (bem/kernels/transmission_parameters.hpp):
// dense assembly and a partial-pivot LU of the direct first-kind system, discretised by P0
// Galerkin (bem/operators/galerkin_operators.hpp). With φ = s_i|Γ and q = ∂_n s_i from inside
// (docs/theory.md derives it):
//
//   V0 q − (½M + K0) φ = 0                 interior Green identity (Laplace)
//   Vκ q − (Kκ − ½M) φ = Vκ g,  g = n_i/ã   exterior Green identity (Yukawa) with q_out = q − g
//
// M = diag(|T_j|) is the P0 mass matrix.
//
// The three directions share the matrix: one factorisation, three right-hand sides.
// Memory: (2N)² doubles for the matrix (32·N² bytes), checked before allocation.

#include <cstdint>

#include "bem/solve/boundary_solution.hpp"
#include "core/progress.hpp"
#include "geometry/surface_mesh.hpp"

namespace bemshape::bem {

struct DenseSolverOptions {
  /// Upper bound on the memory of the dense matrix [bytes]; 0 = what the machine has.
  std::uint64_t max_memory_bytes = 0;
};

/// Bytes the dense path allocates for a mesh of `faces` faces.
std::uint64_t dense_solver_memory_bytes(Eigen::Index faces);

/// The dense path's bound on the process's peak for `faces` faces [bytes]: `held_bytes` (what
/// the process holds already), the system and its copy with a margin for the heap's rounding,
/// and the panels, tables of touching pairs and work arrays per face. The guard of
/// solve_transmission_dense refuses where it exceeds the budget; --fit-memory inverts it.
std::uint64_t dense_solver_peak_bytes(Eigen::Index faces, std::uint64_t held_bytes);

/// Solves for s_1, s_2, s_3 on a closed, outward-oriented mesh. Throws ResourceError if the
/// matrix would not fit and NumericalError if the factorisation is singular or the solution
/// is not finite.
BoundarySolution solve_transmission_dense(const geometry::SurfaceMesh& mesh,
                                          const TransmissionParameters& parameters,
                                          const DenseSolverOptions& options = {},
                                          const ProgressCallback& progress = {});

}  // namespace bemshape::bem
