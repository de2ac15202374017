#pragma once
// The refusal of a BEM solver whose memory estimate is over the budget, with the figures a
// coarser mesh that fits is chosen from (analysis/memory_budget.hpp, fitting_solver_faces).
// Its own header so that the figures it carries can change without rebuilding every user of
// core/errors.hpp.

#include <string>

#include "core/errors.hpp"

namespace bemshape {

/// A BEM solver's memory estimate for its mesh over the budget, refused before the system is
/// allocated (a ResourceError: exit code 2 where nothing takes a coarser mesh).
class SolverMemoryRefusal : public ResourceError {
 public:
  /// Which solver's bound `needed_bytes` is: the dense one is a closed form in the face count
  /// (bem::dense_solver_peak_bytes), the hierarchical-matrix one depends on the geometry.
  enum class Solver { dense, hmatrix };
  SolverMemoryRefusal(const std::string& message, Solver solver, long faces,
                      double needed_bytes, double budget_bytes, double held_bytes)
      : ResourceError(message),
        solver(solver),
        faces(faces),
        needed_bytes(needed_bytes),
        budget_bytes(budget_bytes),
        held_bytes(held_bytes) {}
  Solver solver;
  long faces;           ///< solver faces of the refused mesh
  double needed_bytes;  ///< the solver's estimate of the process's peak [bytes]
  double budget_bytes;  ///< what may be used [bytes]
  double held_bytes;    ///< part of the estimate the process holds whatever the mesh [bytes]
};

}  // namespace bemshape
