#include "apps/run_limits.hpp"

#include <csignal>
#include <cmath>
#include <cstdlib>

#include "core/cancellation.hpp"
#include "core/errors.hpp"

namespace bemshape::apps {
namespace {

/// Longest accepted --timeout [s] (a year): beyond it the steady clock's tick count could
/// overflow, and no run is meant to take longer.
constexpr double kMaxTimeoutSeconds = 365.0 * 24 * 3600;

extern "C" void request_cancellation_on_signal(int signal) {
  request_cancellation(signal);
}

}  // namespace

std::uint64_t parse_memory_size(const std::string& text, const std::string& option) {
  const auto refuse = [&]() -> std::uint64_t {
    throw InputError(option + " '" + text +
                     "': expected a positive size: a number of MB or a number with a unit "
                     "K, M, G, T (powers of 1000) or KiB, MiB, GiB, TiB (powers of 1024), "
                     "e.g. 800MB or 2G");
  };
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin || !std::isfinite(value) || !(value > 0.0)) return refuse();
  std::string unit(end);
  while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
  for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  double scale = 0.0;
  if (unit.empty()) scale = 1e6;
  else if (unit == "B") scale = 1.0;
  else if (unit == "K" || unit == "KB") scale = 1e3;
  else if (unit == "M" || unit == "MB") scale = 1e6;
  else if (unit == "G" || unit == "GB") scale = 1e9;
  else if (unit == "T" || unit == "TB") scale = 1e12;
  else if (unit == "KIB") scale = 1024.0;
  else if (unit == "MIB") scale = 1024.0 * 1024.0;
  else if (unit == "GIB") scale = 1024.0 * 1024.0 * 1024.0;
  else if (unit == "TIB") scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
  else return refuse();
  const double bytes = value * scale;
  if (!(bytes >= 1.0 && bytes < 1.8e19)) return refuse();
  return static_cast<std::uint64_t>(bytes);
}

void add_timeout_option(CLI::App& command) {
  command
      .add_option_function<double>(
          "--timeout",
          [](double seconds) {
            if (!(seconds > 0.0 && seconds <= kMaxTimeoutSeconds))
              throw InputError("--timeout must be a positive number of seconds (at most a "
                               "year), got " + std::to_string(seconds));
            set_deadline(seconds);
          },
          "Stop the run after this many seconds (exit code 3, no output written)")
      ->type_name("SECONDS");
}

void add_max_memory_option(CLI::App& command, std::uint64_t& bytes) {
  command
      .add_option_function<std::string>(
          "--max-memory",
          [&bytes](const std::string& text) { bytes = parse_memory_size(text, "--max-memory"); },
          "Memory limit of the large allocations: MB, or with a unit, e.g. 800MB, 2G, 1.5GiB "
          "(default: what the machine has)")
      ->type_name("SIZE");
}

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = request_cancellation_on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace bemshape::apps
