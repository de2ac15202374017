#pragma once
// `bemshape check INPUT`: reads, validates and repairs a mesh file and prints what it found
// and did. Exit code 0 if the mesh is usable (possibly after repairs), 2 if it is refused or
// cannot be read.

#include <CLI/CLI.hpp>
#include <functional>

namespace bemshape::apps {

/// Adds the `check` subcommand to `app`. When it runs, it stores its exit code in
/// `exit_code`; refusals are thrown as InputError for main() to print.
void register_check_command(CLI::App& app, int& exit_code);

}  // namespace bemshape::apps
