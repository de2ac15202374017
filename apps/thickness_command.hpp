#pragma once
// `bemshape thickness INPUT [--h0 L] [--a 0.2] [--measure principal|paper]
//  [--min-thickness T] [--max-edge E] [-o OUT.vtp|.ply|.csv] [--report REPORT.json]
//  [--html REPORT.html]
//  [--threads N] [--quiet] [--max-memory SIZE] [--timeout S]`: the local wall thickness of a
// solid part on its surface, and optionally the CAD minimum-wall-thickness check.
//
// Pipeline: read, validate, repair → refine to the solver's element size → dense BEM solve
// → features on the refined surface → statistics and thin regions (on the refined faces) →
// values carried back to the input mesh's vertices and faces for the output file. Exit code
// 0, or 1 if --min-thickness is given and some face is thinner. docs/usage.md documents the
// report and the files.

#include <CLI/CLI.hpp>

namespace bemshape::apps {

/// Adds the `thickness` subcommand to `app`; stores its exit code in `exit_code` when it runs.
void register_thickness_command(CLI::App& app, int& exit_code);

}  // namespace bemshape::apps
