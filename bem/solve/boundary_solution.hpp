#pragma once
// The boundary data of the shape-feature solution, for the three coordinate directions.
//
//   phi(f, i) = s_i on face f (P0: the value at the face centroid) [model units]
//   q(f, i)   = ∂_n s_i on face f from INSIDE the solid [dimensionless]
//
// The exterior normal derivative follows from the jump: q_out = q − n_i/ã.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "bem/kernels/transmission_parameters.hpp"

namespace bemshape::bem {

/// What a solver reports about its run (copied into the JSON report by apps/).
struct SolveReport {
  std::string method;             ///< "dense-lu", …
  Eigen::Index unknowns = 0;      ///< size of the linear system
  int iterations = 0;             ///< Krylov iterations (0 for a direct solve)
  /// Restart length of the Krylov solver (0 for a direct solve): the one asked for, or less
  /// where its basis would not fit in the memory allowed.
  int restart = 0;
  double residual = 0.0;          ///< max over right-hand sides of ‖A x − b‖ / ‖b‖
  /// max over right-hand sides of ‖M⁻¹(A x − b)‖ / ‖M⁻¹b‖ for a left-preconditioned Krylov
  /// solve, the quantity its tolerance bounds (an estimate of the solution's relative
  /// error); equal to `residual` otherwise
  double preconditioned_residual = 0.0;
  double assembly_seconds = 0.0;  ///< wall time of the operator assembly
  double solve_seconds = 0.0;     ///< wall time of the factorisation and solves
  /// Stages of the assembly, in order (name, wall time [s]); empty for the dense path, whose
  /// assembly is one stage.
  std::vector<std::pair<std::string, double>> assembly_stages;
  /// Where the solve's wall time went (name, seconds); empty for the dense path.
  std::vector<std::pair<std::string, double>> solve_stages;
  std::uint64_t operator_bytes = 0;  ///< memory held by the assembled operators [bytes]
  /// The memory guard's bound on the process's resident size during the solve [bytes]
  /// (what it held before, the operators, the solver's work arrays), checked against the
  /// budget before anything was assembled.
  std::uint64_t memory_estimate_bytes = 0;
  /// operator_bytes by part, in the order of assembly_stages (name, bytes); empty for the
  /// dense path.
  std::vector<std::pair<std::string, std::uint64_t>> operator_parts;
  double compression = 0.0;  ///< stored / dense entries of the compressed part (0: not compressed)
};

struct BoundarySolution {
  Eigen::MatrixX3d phi;  ///< #F×3, s_i on each face
  Eigen::MatrixX3d q;    ///< #F×3, interior normal derivative of s_i on each face
  TransmissionParameters parameters;
  SolveReport report;
};

}  // namespace bemshape::bem
