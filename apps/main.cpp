// The bemshape program: one CLI11 subcommand per file (check_command.cpp, ...), and the one
// place where exceptions become messages on stderr and exit codes (exit_codes.hpp):
//   InputError, ResourceError, CLI usage errors → 2;  NumericalError, internal errors → 3;
//   CancelledError → 3 for --timeout, 128 + signal for SIGINT/SIGTERM (run_limits.hpp).
// Every error is printed as one line "bemshape: error: <what>" followed by any details.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include "apps/check_all_command.hpp"
#include "apps/check_command.hpp"
#include "apps/compare_command.hpp"
#include "apps/exit_codes.hpp"
#include "apps/features_command.hpp"
#include "apps/fem_command.hpp"
#include "apps/run_limits.hpp"
#include "apps/thickness_command.hpp"
#include "core/errors.hpp"
#include "core/heap_retention.hpp"
#include "core/huge_pages.hpp"

namespace {

int print_error(const std::string& message, int code) {
  std::cerr << "bemshape: error: " << message << '\n';
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace bemshape;
  restart_with_heap_huge_pages(argv);  // once, before anything is allocated: 2 MB heap pages
  retain_freed_heap_memory();  // the solvers' temporaries are reused, not page-faulted again
  pad_heap_growth();           // the assembly threads' heaps get huge pages too
  CLI::App app{
      "bemshape: local wall thickness, orientation and skeleton of solid parts given as closed "
      "triangle meshes (STL, OBJ, OFF, PLY, 3MF). Lengths are in the units of the input file."};
  // The instruction set the build targets (BEMSHAPE_ARCH): timings depend on it.
  app.set_version_flag("--version", std::string("bemshape ") + BEMSHAPE_VERSION + " (-march=" +
                                        (*BEMSHAPE_ARCH_NAME ? BEMSHAPE_ARCH_NAME : "compiler default") + ")");
  app.require_subcommand(1, 1);
  app.fallthrough(false);

  int exit_code = apps::kExitSuccess;
  apps::register_check_command(app, exit_code);
  apps::register_thickness_command(app, exit_code);
  apps::register_features_command(app, exit_code);
  apps::register_fem_command(app, exit_code);
  apps::register_compare_command(app, exit_code);
  apps::register_check_all_command(app, exit_code);

  apps::install_interrupt_handlers();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return print_error(std::string(e.what()) + " (run 'bemshape --help')", apps::kExitBadInput);
  } catch (const InputError& e) {
    return print_error(e.what(), apps::kExitBadInput);
  } catch (const ResourceError& e) {
    return print_error(e.what(), apps::kExitBadInput);
  } catch (const NumericalError& e) {
    return print_error(e.what(), apps::kExitNumericalFailure);
  } catch (const CancelledError& e) {
    return print_error(e.what(), e.signal() != 0 ? apps::exit_code_for_signal(e.signal())
                                                 : apps::kExitTimedOut);
  } catch (const std::bad_alloc&) {
    return print_error("out of memory", apps::kExitBadInput);
  } catch (const std::exception& e) {
    return print_error(std::string("internal error (please report): ") + e.what(),
                       apps::kExitNumericalFailure);
  }
  return exit_code;
}
