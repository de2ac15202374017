#pragma once
// `bemshape check-all INPUT... [--list FILE] --min-thickness T --reports DIR [--jobs N]
//  [--threads N] [--timeout S] [--resume] [--summary FILE] [--quiet] [thickness options]`:
// the minimum-wall check of many parts, a release gate. Each part runs as its own
// `bemshape thickness PART --report DIR/<part>.json` process, --jobs of them at a time
// (apps/child_process.hpp), so a part that crashes, runs out of memory or hangs stops alone.
// One JSON report per part (written atomically), one JSON-lines summary
// (apps/part_summary.hpp) in the parts' order, one line per finished part on stdout, and an
// exit code for the set: 0 every part passes, 1 some part has thinner walls, 2 some part
// has no verdict (unreadable, refused, failed, timed out). --resume keeps the parts whose
// report is complete; SIGINT stops the running parts cleanly (no report half-written),
// writes the summary of what was checked and exits 130. docs/usage.md, "bemshape check-all".

#include <CLI/CLI.hpp>

namespace bemshape::apps {

/// Adds the `check-all` subcommand to `app`; stores its exit code in `exit_code` when it runs.
void register_check_all_command(CLI::App& app, int& exit_code);

}  // namespace bemshape::apps
