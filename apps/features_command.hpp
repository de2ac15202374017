#pragma once
// `bemshape features INPUT (--points PTS.csv | --grid SPACING) [-o OUT.csv|.vti] [--h0 L]
//  [--a 0.2] [--max-edge E] [--skeleton-width W] [--threads N] [--quiet] [--max-memory SIZE]
//  [--timeout S]`:
// the shape features inside the solid, at the user's points or on a regular grid over the
// part's bounding box, by the boundary integral representation (bem/evaluate/potential_evaluation.hpp)
// — no volume mesh. Per point: inside flag, s, f_h, h_f, h_p, n_f, skeleton. docs/usage.md
// documents the columns.

#include <CLI/CLI.hpp>

namespace bemshape::apps {

/// Adds the `features` subcommand to `app`; stores its exit code in `exit_code` when it runs.
void register_features_command(CLI::App& app, int& exit_code);

}  // namespace bemshape::apps
