#pragma once
// Limits of one bemshape run, shared by the commands that can run long (thickness, features,
// fem, check) so that names, units and help texts cannot drift apart:
//
//   --timeout SECONDS   wall-clock limit; the run stops at the next poll point
//                       (core/cancellation.hpp) with exit code 3 and no output written;
//   --max-memory SIZE   memory budget of the large allocations (core/memory.hpp's guard):
//                       a number of MB, or a number with a unit K, M, G, T (powers of 1000)
//                       or KiB, MiB, GiB, TiB (powers of 1024), e.g. 512, 800MB, 2G, 1.5GiB;
//   SIGINT, SIGTERM     stop the run the same way, exit code 128 + signal (130 for SIGINT);
//                       a second signal ends the process at once (default action).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

namespace bemshape::apps {

/// Bytes in a --max-memory value ("512" = 512 MB, "2G", "1.5GiB", ...). Throws InputError
/// naming `option` for anything else, including zero and negative sizes.
std::uint64_t parse_memory_size(const std::string& text, const std::string& option);

/// Registers --timeout SECONDS on `command`; when given, the deadline starts as the options
/// are parsed, i.e. at the start of the run.
void add_timeout_option(CLI::App& command);

/// Registers --max-memory SIZE on `command`, stored in `bytes` (0 when not given).
void add_max_memory_option(CLI::App& command, std::uint64_t& bytes);

/// Turns SIGINT and SIGTERM into a cancellation request (core/cancellation.hpp); the
/// handler resets itself, so a second signal terminates the process.
void install_interrupt_handlers();

}  // namespace bemshape::apps
