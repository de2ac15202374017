#pragma once
// `bemshape compare INPUT --cell SIZE [--h0 L] [--a 0.2] [--max-edge E] [--sharp-angle A]
//  [--solver auto|dense|hmatrix] [--tolerance T] [--max-probes N] [--report OUT.json]
//  [--threads N] [--quiet] [--timeout SECONDS]`: solves the shape-feature PDE of one closed
// surface mesh twice, by the boundary element method (the `thickness` and `features` path:
// refined solver mesh, transmission solve, representation formula at interior points) and
// by the voxel finite-element method (the `fem` path: the input mesh voxelised with cells of
// side SIZE), and compares f_h and h_p at interior probe points.
//
// Probes: centres of the FEM's solid cells (χ ≥ ½) whose distance to the input surface is at
// least kProbeDepthCells·SIZE, where both solutions are smooth and the FEM's staircase
// boundary does not dominate; at most --max-probes of them, spread evenly over that set.
// At each probe the relative difference is |FEM − BEM| / |BEM| (the BEM is the reference:
// its errors on the closed forms are ten times smaller, docs/validation.md). The report gives
// the median, 95th percentile and maximum for f_h and h_p, as fractions, and a text
// histogram of the h_p differences; --report writes the same as JSON (docs/usage.md).

#include <CLI/CLI.hpp>

namespace bemshape::apps {

/// Adds the `compare` subcommand to `app`; stores its exit code in `exit_code` when it runs.
void register_compare_command(CLI::App& app, int& exit_code);

}  // namespace bemshape::apps
