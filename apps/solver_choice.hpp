#pragma once
// The solver's choice as a front end names it (the command line's --solver, --far-field and
// --tolerance, the Python module's keyword arguments of the same names) and its translation,
// with the PDE's parameters and the solver mesh's, into the library's analysis::SolveOptions.
// No command-line parser here: the Python module includes it too.

#include <cstdint>
#include <optional>
#include <string>

#include "analysis/boundary_solve.hpp"
#include "core/errors.hpp"

namespace bemshape::apps {

/// --solver, --far-field and --tolerance as typed (solver_choice checks the names).
struct SolverChoiceText {
  std::string method = "auto";     ///< auto | dense | hmatrix
  std::optional<double> tolerance;  ///< GMRES relative residual; empty: by what is read
  std::string far_field = "auto";  ///< auto | hmatrix | nested
};

/// The library's solver choice for the typed one. Throws InputError for an unknown name.
inline analysis::SolverChoice solver_choice(const SolverChoiceText& text) {
  analysis::SolverChoice choice;
  if (text.method == "auto")
    choice.method = analysis::SolverMethod::automatic;
  else if (text.method == "dense")
    choice.method = analysis::SolverMethod::dense;
  else if (text.method == "hmatrix")
    choice.method = analysis::SolverMethod::hmatrix;
  else
    throw InputError("solver (--solver) must be auto, dense or hmatrix, got '" + text.method +
                     "'");
  using FarField = bem::HMatrixSolverOptions::FarField;
  if (text.far_field == "auto")
    choice.far_field = FarField::automatic;
  else if (text.far_field == "hmatrix")
    choice.far_field = FarField::hmatrix;
  else if (text.far_field == "nested")
    choice.far_field = FarField::nested;
  else
    throw InputError("far field (--far-field) must be auto, hmatrix or nested, got '" +
                     text.far_field + "'");
  choice.tolerance = text.tolerance;
  return choice;
}

/// The options every solving command shares, as the library takes them.
inline analysis::SolveOptions solve_options(double h0, double a, std::optional<double> max_edge,
                                            std::optional<double> sharp_angle,
                                            const SolverChoiceText& solver,
                                            std::uint64_t max_memory_bytes) {
  analysis::SolveOptions options;
  options.h0 = h0;
  options.a = a;
  options.max_edge = max_edge;
  options.sharp_angle_degrees = sharp_angle;
  options.solver = solver_choice(solver);
  options.max_memory_bytes = max_memory_bytes;
  return options;
}

}  // namespace bemshape::apps
