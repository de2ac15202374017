#pragma once
// The command-line options that shape the solver mesh and choose the solver, shared by every
// command that solves (thickness, features, compare), so their names, units and help texts
// cannot drift apart. Their translation into the library's analysis::SolveOptions is in
// apps/solver_choice.hpp.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "analysis/boundary_solve.hpp"
#include "apps/solver_choice.hpp"

namespace bemshape::apps {

/// Registers --max-edge (the remesher's target edge length [model units]; empty = the
/// default of what is read: analysis::SolverMeshRule) and --sharp-angle (crease angle of the
/// remesher [degrees]).
inline void add_solver_mesh_options(CLI::App& command, std::optional<double>& max_edge,
                                    std::optional<double>& sharp_angle) {
  command.add_option("--max-edge", max_edge,
                     "Element edge length of the solver mesh, in file units: the remesher's target, no edge longer than 1.3 times it (default: for thickness --measure wall a graded mesh whose elements follow the walls, at most 4*h0; otherwise 1.5*a*h0)");
  command
      .add_option("--sharp-angle", sharp_angle,
                  "Edges with a dihedral angle above this [degrees] are kept as creases when "
                  "remeshing (default: 1, every crease of the input; for thickness --measure wall "
                  "5, measured between the face normals averaged over h0/2 with the part's edges "
                  "kept, so that a scanned or noisy surface's roughness is no crease); 30 lets "
                  "the remesher cross the facets of tessellated curved surfaces");
}

/// Registers --solver (auto | dense | hmatrix), --far-field (auto | hmatrix | nested) and
/// --tolerance (GMRES relative residual).
inline void add_solver_choice_options(CLI::App& command, SolverChoiceText& choice) {
  command
      .add_option("--solver", choice.method,
                  "Linear solver: dense (LU, exact, O(N^2) memory), hmatrix (H-matrix + GMRES, "
                  "for large meshes) or auto (dense up to " +
                      std::to_string(analysis::kAutoDenseFaces) + " solver faces, " +
                      std::to_string(analysis::kAutoDenseGradedFaces) +
                      " on the wall reading's graded mesh)")
      ->check(CLI::IsMember({"auto", "dense", "hmatrix"}))
      ->capture_default_str();
  command
      .add_option("--far-field", choice.far_field,
                  "How the hmatrix solver keeps the far field of the interior operators: hmatrix "
                  "(fastest), nested (H2 form: about a third less far-field memory, a slower assembly) or "
                  "auto (nested only where hmatrix would not fit in memory)")
      ->check(CLI::IsMember({"auto", "hmatrix", "nested"}))
      ->capture_default_str();
  command
      .add_option("--tolerance", choice.tolerance,
                  "Relative residual the hmatrix solver's GMRES must reach (default: 1e-6; for "
                  "thickness --measure wall 1e-5, which moves the readings by less than 1e-5 "
                  "of the wall)")
      ->check(CLI::Range(1e-14, 0.1));
}

}  // namespace bemshape::apps
