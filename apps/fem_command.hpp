#pragma once
// `bemshape fem INPUT --cell SIZE [--h0 L] [--a 0.2] [--invert] [--pixel SIZE]
//  [--dims NX,NY,NZ] [--samples K] [-o OUT]`: the voxel finite-element path. INPUT is a 2-D
// PNG (black = solid), a folder of PNG slices or a raw byte volume (with --dims), or a
// closed surface mesh (voxelised by an exact inside test). Writes OUT (.vti, cell data:
// chi, s, f_h, h_f, h_p, n_f, skeleton) and for 2-D input also OUT_<field>.png pictures.
// Without --h0, h0 is analysis::kDefaultH0Cells cells (analysis/voxel_resolution.hpp).

#include <CLI/CLI.hpp>

namespace bemshape::apps {

/// Adds the `fem` subcommand to `app`; stores its exit code in `exit_code` when it runs.
void register_fem_command(CLI::App& app, int& exit_code);

}  // namespace bemshape::apps
