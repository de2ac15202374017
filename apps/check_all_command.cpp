#include "apps/check_all_command.hpp"

#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/child_process.hpp"
#include "apps/exit_codes.hpp"
#include "apps/output/atomic_file.hpp"
#include "apps/part_list.hpp"
#include "apps/part_summary.hpp"
#include "apps/run_limits.hpp"
#include "apps/solver_mesh_options.hpp"
#include "core/cancellation.hpp"
#include "core/errors.hpp"
#include "core/memory.hpp"
#include "core/number_text.hpp"

namespace bemshape::apps {
namespace {

namespace fs = std::filesystem;

struct CheckAllOptions {
  std::vector<std::string> inputs;
  std::vector<std::string> lists;
  std::string reports;
  std::string summary;
  int jobs = 1;
  int threads = 0;
  std::optional<double> timeout;
  bool resume = false;
  bool quiet = false;
  // Passed to every part's `bemshape thickness`, with the same meaning.
  double min_thickness = 0.0;
  std::optional<double> h0;
  double a = 0.2;
  std::string measure = "wall";
  std::string edges = "wall";
  std::optional<double> max_thickness;
  std::optional<double> min_region_area;
  std::optional<double> max_edge;
  std::optional<double> sharp_angle;  // empty: the solver mesh rule's default
  SolverChoiceText solver;
  std::uint64_t max_memory_bytes = 0;
  bool fit_memory = false;  // --fit-memory, passed to every part
};

/// Seconds a part may run past --timeout before it is sent SIGTERM, and again before
/// SIGKILL: its own --timeout stops it at its next poll point, within a second on a quiet
/// machine and 10 s on a loaded one (docs/reliability.md, "Run limits"); only a part stuck
/// outside the poll points needs the signals.
constexpr double kTimeoutGraceSeconds = 30.0;
/// Seconds the running parts get to stop after SIGINT before they are killed (SIGKILL): as
/// long as a --timeout needs to take effect.
constexpr double kInterruptGraceSeconds = 30.0;
/// How long one wait for the parts' output lasts [s]: the interval at which timeouts,
/// signals and the progress line are looked at.
constexpr int kPollMilliseconds = 100;
/// Significant digits of the numbers passed to the parts: every double survives the round
/// trip through text.
constexpr int kExactDigits = 17;

/// The file of the run's options beside the reports: --resume refuses reports made with
/// other options.
constexpr const char* kRunFileName = "check-all.json";

/// The options every part's `bemshape thickness` gets that shape its result (threads,
/// memory and timeout do not: they are added per run).
std::vector<std::string> result_arguments(const CheckAllOptions& o) {
  std::vector<std::string> args = {"--min-thickness",
                                   number_text(o.min_thickness, kExactDigits),
                                   "--a",
                                   number_text(o.a, kExactDigits),
                                   "--measure",
                                   o.measure,
                                   "--edges",
                                   o.edges,
                                   "--solver",
                                   o.solver.method,
                                   "--far-field",
                                   o.solver.far_field};
  const auto add = [&args](const char* name, const std::optional<double>& value) {
    if (value) {
      args.push_back(name);
      args.push_back(number_text(*value, kExactDigits));
    }
  };
  add("--h0", o.h0);
  add("--tolerance", o.solver.tolerance);
  add("--sharp-angle", o.sharp_angle);
  add("--max-thickness", o.max_thickness);
  add("--min-region-area", o.min_region_area);
  add("--max-edge", o.max_edge);
  if (o.fit_memory)
    args.push_back("--fit-memory");
  return args;
}

void validate(const CheckAllOptions& o) {
  const auto positive = [](const char* name, std::optional<double> value) {
    if (value && !(std::isfinite(*value) && *value > 0.0))
      throw InputError(std::string(name) + " must be a positive number, got " +
                       number_text(*value, 6));
  };
  positive("--min-thickness", o.min_thickness);
  positive("--h0", o.h0);
  positive("--max-thickness", o.max_thickness);
  positive("--max-edge", o.max_edge);
  positive("--timeout", o.timeout);
  if (o.jobs < 1)
    throw InputError("--jobs must be at least 1, got " + std::to_string(o.jobs));
  if (o.threads < 0)
    throw InputError("--threads must be positive, got " + std::to_string(o.threads));
}

/// Reads a JSON file; nullopt if it is missing or not JSON.
std::optional<nlohmann::json> read_json_file(const fs::path& path) {
  std::ifstream in(path);
  if (!in)
    return std::nullopt;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

/// Writes REPORTS/check-all.json, or with --resume checks that the reports there were made
/// with the same options.
void record_run_options(const CheckAllOptions& o, const fs::path& reports,
                        const std::vector<std::string>& arguments) {
  const fs::path run_file = reports / kRunFileName;
  const nlohmann::json run = {
      {"bemshape", BEMSHAPE_VERSION}, {"command", "check-all"}, {"part_options", arguments}};
  if (o.resume) {
    if (const auto previous = read_json_file(run_file);
        previous && previous->value("part_options", nlohmann::json()) != run["part_options"]) {
      std::string before;
      for (const auto& a : previous->value("part_options", nlohmann::json::array()))
        before += (before.empty() ? "" : " ") + a.get<std::string>();
      throw InputError(reports.string() + ": its reports were made with other options (" + before +
                       "); drop --resume to check every part again, or use another "
                       "--reports folder");
    }
  }
  output::write_file_atomically(run_file, run.dump(2) + '\n');
}

/// The part's report if it is complete and of this part, else nullopt.
std::optional<nlohmann::json> complete_report(const Part& part) {
  auto report = read_json_file(part.report);
  if (!report || !report->is_object() || report->value("command", "") != "thickness" ||
      report->value("input", "") != part.path || !report->contains("check") ||
      !(*report)["check"].is_object())
    return std::nullopt;
  return report;
}

/// Removes the temporaries a killed part's AtomicFileWriter left beside its report.
void remove_temporaries(const fs::path& report) {
  const std::string prefix = "." + report.filename().string() + ".tmp-";
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(report.parent_path(), error))
    if (entry.path().filename().string().rfind(prefix, 0) == 0)
      fs::remove(entry.path(), error);
}

/// The error a part's process wrote: from its first "bemshape: error: " line on, without the
/// prefix; else its last line.
std::string error_message(const std::string& errors) {
  static const std::string prefix = "bemshape: error: ";
  std::string text;
  if (const auto at = errors.find(prefix); at != std::string::npos)
    text = errors.substr(at + prefix.size());
  else if (!errors.empty()) {
    const auto end = errors.find_last_not_of('\n');
    const auto start = end == std::string::npos ? 0 : errors.rfind('\n', end);
    text = errors.substr(start == std::string::npos ? 0 : start + 1);
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
    text.pop_back();
  return text;
}

/// The one line stdout gets for a finished part.
std::string part_line(std::size_t done, std::size_t total, const nlohmann::ordered_json& record) {
  const int width = static_cast<int>(std::to_string(total).size());
  char counter[48];
  std::snprintf(counter, sizeof counter, "[%*zu/%zu]", width, done, total);
  std::ostringstream line;
  const std::string verdict = record["verdict"];
  line << counter << ' ' << verdict
       << std::string(12 - std::min<std::size_t>(verdict.size(), 11), ' ');
  if (record["min_thickness"].is_number())
    line << "min " << number_text(record["min_thickness"].get<double>(), 6) << ", "
         << record["regions"].get<std::size_t>() << " thin region"
         << (record["regions"].get<std::size_t>() == 1 ? "" : "s") << ", ";
  line << number_text(record["seconds"].get<double>(), 3) << " s"
       << (record["resumed"].get<bool>() ? " (resumed)" : "") << "  "
       << record["part"].get<std::string>();
  if (record["error"].is_string()) {
    const std::string error = record["error"];
    line << ": " << error.substr(0, error.find('\n'));
  }
  if (record.contains("units_warning") && record["units_warning"].is_string())
    line << "\n    " << record["units_warning"].get<std::string>();
  return line.str();
}

/// The running count on stderr when it is a terminal: one line rewritten in place.
class CountLine {
 public:
  explicit CountLine(bool quiet) : live_(!quiet && ::isatty(STDERR_FILENO)) {}
  void draw(const std::string& text) {
    if (!live_)
      return;
    std::cerr << "\r\033[K" << text << std::flush;
    drawn_ = true;
  }
  void erase() {
    if (live_ && drawn_)
      std::cerr << "\r\033[K" << std::flush;
    drawn_ = false;
  }

 private:
  bool live_;
  bool drawn_ = false;
};

struct Running {
  std::size_t part;
  std::unique_ptr<ChildProcess> process;
  bool terminated = false;  ///< SIGTERM sent (timeout)
  bool killed = false;      ///< SIGKILL sent
};

class CheckAllRun {
 public:
  CheckAllRun(const CheckAllOptions& options, std::vector<Part> parts, int threads,
              std::uint64_t part_memory_bytes)
      : o_(options),
        parts_(std::move(parts)),
        records_(parts_.size()),
        threads_(threads),
        part_memory_bytes_(part_memory_bytes),
        count_line_(options.quiet) {}

  /// Checks every part; returns the set's exit code, or throws CancelledError after a
  /// signal once the summary is written.
  int run(const std::vector<std::string>& arguments, const fs::path& summary) {
    const std::string self = fs::read_symlink("/proc/self/exe").string();
    std::vector<std::size_t> queue;
    for (std::size_t i = 0; i < parts_.size(); ++i) {
      if (o_.resume)
        if (const auto report = complete_report(parts_[i])) {
          finish(i, part_summary_from_report(parts_[i].path, *report, parts_[i].report.string(),
                                             true));
          continue;
        }
      queue.push_back(i);
    }
    // Largest file first (a part's time grows with its size): the set then ends with small
    // parts, and no core idles long beside the last part's job (longest-processing-time-first
    // scheduling). The summary keeps the parts' own order.
    std::vector<std::uintmax_t> bytes(parts_.size(), 0);
    for (const std::size_t i : queue) {
      std::error_code error;
      const std::uintmax_t size = fs::file_size(parts_[i].path, error);
      bytes[i] = error ? 0 : size;
    }
    std::stable_sort(queue.begin(), queue.end(),
                     [&](std::size_t a, std::size_t b) { return bytes[a] > bytes[b]; });
    std::size_t next = 0;
    int stop_signal = 0;
    while (next < queue.size() || !running_.empty()) {
      if (stop_signal == 0 && cancellation_requested()) {
        stop_signal = detail::cancellation_signal.load();
        if (stop_signal == 0)
          stop_signal = SIGINT;
        for (Running& r : running_)
          r.process->send(stop_signal);
        stop_time_ = ChildProcess::Clock::now();
      }
      while (stop_signal == 0 && running_.size() < std::size_t(o_.jobs) && next < queue.size())
        start(queue[next++], self, arguments);
      if (stop_signal != 0 && running_.empty())
        break;
      wait_for_output();
      reap(stop_signal);
      draw_count();
    }
    count_line_.erase();
    for (std::size_t i = 0; i < parts_.size(); ++i)
      if (records_[i].is_null())
        records_[i] = part_summary_without_report(
            parts_[i].path, kVerdictInterrupted, "not checked: the set was interrupted",
            exit_code_for_signal(stop_signal), o_.min_thickness, 0.0, std::nullopt);
    write_summary(summary);
    print_totals(summary);
    if (stop_signal != 0)
      throw CancelledError("interrupted by signal " + std::to_string(stop_signal) + ": " +
                               std::to_string(done_ - interrupted_) + " of " +
                               std::to_string(parts_.size()) + " parts checked (summary " +
                               summary.string() +
                               "); no report was left half-written; run "
                               "again with --resume to check the rest",
                           stop_signal);
    if (errors_ > 0)
      return kExitBadInput;
    return thin_ > 0 ? kExitCheckFailed : kExitSuccess;
  }

 private:
  void start(std::size_t i, const std::string& self, const std::vector<std::string>& arguments) {
    const Part& part = parts_[i];
    std::error_code error;
    fs::create_directories(part.report.parent_path(), error);
    // A report from an earlier run must not outlive a run of the part that fails.
    fs::remove(part.report, error);
    std::vector<std::string> argv = {self,
                                     "thickness",
                                     part.path,
                                     "--report",
                                     part.report.string(),
                                     "--quiet",
                                     "--threads",
                                     std::to_string(threads_)};
    argv.insert(argv.end(), arguments.begin(), arguments.end());
    if (part_memory_bytes_ > 0) {
      argv.push_back("--max-memory");
      argv.push_back(std::to_string(part_memory_bytes_) + "B");
    }
    if (o_.timeout) {
      argv.push_back("--timeout");
      argv.push_back(number_text(*o_.timeout, kExactDigits));
    }
    running_.push_back({i, std::make_unique<ChildProcess>(argv)});
  }

  void wait_for_output() {
    std::vector<pollfd> fds;
    for (const Running& r : running_)
      if (r.process->error_fd() >= 0)
        fds.push_back({r.process->error_fd(), POLLIN, 0});
    // Children whose pipe has closed end without output: poll() alone would not wake for
    // them, so the wait is bounded.
    ::poll(fds.data(), fds.size(), kPollMilliseconds);
    for (Running& r : running_)
      r.process->read_errors();
  }

  void reap(int stop_signal) {
    const auto now = ChildProcess::Clock::now();
    for (auto it = running_.begin(); it != running_.end();) {
      ChildProcess& p = *it->process;
      if (!p.try_reap()) {
        if (stop_signal != 0) {
          // Interrupted: the part had its signal; past the grace it is killed.
          if (!it->killed &&
              std::chrono::duration<double>(now - stop_time_).count() > kInterruptGraceSeconds) {
            p.send(SIGKILL);
            it->killed = true;
          }
        } else if (o_.timeout) {
          // Past its own --timeout and the grace: SIGTERM, one more grace later SIGKILL.
          const double over = p.seconds() - *o_.timeout - kTimeoutGraceSeconds;
          if (over > 0.0 && !it->terminated) {
            p.send(SIGTERM);
            it->terminated = true;
          } else if (over > kTimeoutGraceSeconds && !it->killed) {
            p.send(SIGKILL);
            it->killed = true;
          }
        }
        ++it;
        continue;
      }
      finish(it->part, record_of_ended(parts_[it->part], p, stop_signal));
      it = running_.erase(it);
    }
  }

  nlohmann::ordered_json record_of_ended(const Part& part, const ChildProcess& p, int stop_signal) {
    const int code = p.end_signal() != 0 ? exit_code_for_signal(p.end_signal()) : p.exit_code();
    if (code == kExitSuccess || code == kExitCheckFailed) {
      if (const auto report = complete_report(part))
        return part_summary_from_report(part.path, *report, part.report.string(), false);
    }
    remove_temporaries(part.report);
    const double peak_mb = double(p.peak_resident_bytes()) / 1e6;
    const bool timed_out = o_.timeout && p.seconds() >= *o_.timeout && code != kExitSuccess &&
                           code != kExitCheckFailed && stop_signal == 0;
    std::string error = error_message(p.errors());
    if (p.end_signal() != 0 && (stop_signal == 0 || p.end_signal() != stop_signal))
      error = "the part's process was ended by signal " + std::to_string(p.end_signal()) +
              (error.empty() ? "" : " (" + error + ")");
    if (error.empty())
      error = "the part's process exited with code " + std::to_string(code) + " and no message";
    const char* verdict = timed_out ? kVerdictTimeout
                          : stop_signal != 0 && code == exit_code_for_signal(stop_signal)
                              ? kVerdictInterrupted
                              : kVerdictError;
    return part_summary_without_report(part.path, verdict, error, code, o_.min_thickness,
                                       p.seconds(), peak_mb);
  }

  void finish(std::size_t i, nlohmann::ordered_json record) {
    ++done_;
    const std::string verdict = record["verdict"];
    if (verdict == kVerdictPass)
      ++pass_;
    else if (verdict == kVerdictThin)
      ++thin_;
    else if (verdict == kVerdictInterrupted)
      ++interrupted_;
    else
      ++errors_;
    count_line_.erase();
    std::cout << part_line(done_, parts_.size(), record) << std::endl;
    records_[i] = std::move(record);
  }

  void draw_count() {
    count_line_.draw("check-all: " + std::to_string(done_) + "/" + std::to_string(parts_.size()) +
                     " parts done (" + std::to_string(pass_) + " pass, " + std::to_string(thin_) +
                     " thin, " + std::to_string(errors_) + " without verdict), " +
                     std::to_string(running_.size()) + " running");
  }

  void write_summary(const fs::path& summary) const {
    std::string lines;
    for (const nlohmann::ordered_json& record : records_)
      lines += record.dump() + '\n';
    // Written even after SIGINT: the summary of what was checked is the point of stopping
    // cleanly.
    clear_cancellation();
    output::write_file_atomically(summary, lines);
  }

  void print_totals(const fs::path& summary) const {
    std::cout << "check-all: " << parts_.size() << " part" << (parts_.size() == 1 ? "" : "s")
              << ": " << pass_ << " pass, " << thin_ << " thin, " << errors_ << " without verdict";
    if (interrupted_ > 0 || done_ < parts_.size())
      std::cout << ", " << parts_.size() - (done_ - interrupted_) << " not checked";
    std::cout << "; summary " << summary.string() << '\n';
    std::cout.flush();
  }

  const CheckAllOptions& o_;
  std::vector<Part> parts_;
  std::vector<nlohmann::ordered_json> records_;
  int threads_;
  std::uint64_t part_memory_bytes_;
  CountLine count_line_;
  std::vector<Running> running_;
  ChildProcess::Clock::time_point stop_time_{};
  std::size_t done_ = 0, pass_ = 0, thin_ = 0, errors_ = 0, interrupted_ = 0;
};

void run_check_all(const CheckAllOptions& o, int& exit_code) {
  validate(o);
  const fs::path reports(o.reports);
  std::error_code error;
  fs::create_directories(reports, error);
  if (!fs::is_directory(reports))
    throw InputError(o.reports + ": cannot create the reports folder (--reports)" +
                     (error ? ": " + error.message() : ""));
  std::vector<Part> parts = list_parts(o.inputs, o.lists, reports);
  const fs::path summary = o.summary.empty() ? reports / "summary.jsonl" : fs::path(o.summary);
  if (!summary.parent_path().empty() && !fs::is_directory(summary.parent_path()))
    throw InputError(summary.string() + ": the folder of --summary does not exist");
  const std::vector<std::string> arguments = result_arguments(o);
  record_run_options(o, reports, arguments);
  // jobs × threads ≤ cores, every job at least one thread; memory shared out the same way.
  const int cores = std::max(1, omp_get_num_procs());
  const int threads = o.threads > 0 ? o.threads : std::max(1, cores / o.jobs);
  const std::uint64_t part_memory =
      o.max_memory_bytes > 0 ? o.max_memory_bytes : memory_budget_bytes() / std::uint64_t(o.jobs);
  CheckAllRun run(o, std::move(parts), threads, part_memory);
  exit_code = run.run(arguments, summary);
}

}  // namespace

void register_check_all_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CheckAllOptions>();
  CLI::App* cmd = app.add_subcommand(
      "check-all",
      "Minimum-wall check of many parts, each in a process of its own (`thickness` with "
      "--min-thickness): one JSON report per part, a JSON-lines summary, one line per part. "
      "Exit code 0 all pass, 1 some part has thinner walls, 2 some part has no verdict "
      "(unreadable, refused, failed, timed out), 130 interrupted.");
  cmd->add_option("INPUT", o->inputs,
                  "Mesh files (.stl, .obj, .off, .ply, .3mf) and folders (their mesh files, "
                  "recursively)");
  cmd->add_option("--list", o->lists,
                  "A file naming one mesh file or folder per line (# comments); may be repeated");
  cmd->add_option("--min-thickness", o->min_thickness,
                  "The check: a part fails if any wall is thinner than this (file units)")
      ->required();
  cmd->add_option("-r,--reports", o->reports,
                  "Folder of the reports: <part>.json per part (its path relative to the folder "
                  "all parts share), summary.jsonl, check-all.json (the options)")
      ->required();
  cmd->add_option("--summary", o->summary,
                  "The JSON-lines summary, one line per part (default: REPORTS/summary.jsonl)");
  cmd->add_option("-j,--jobs", o->jobs, "Parts checked at the same time, each a process")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads,
                  "Threads per part (default: the cores divided among the jobs)");
  cmd->add_option("--timeout", o->timeout,
                  "Seconds each part may take; a part that takes longer has verdict timeout")
      ->type_name("SECONDS");
  cmd->add_flag("--resume", o->resume,
                "Keep the parts whose report in REPORTS is complete; check the others");
  cmd->add_flag("--quiet", o->quiet, "No running count on stderr");
  cmd->add_option("--h0", o->h0,
                  "Characteristic length, as thickness's --h0 (default: --min-thickness)");
  cmd->add_option("--a", o->a, "Dimensionless diffusion parameter a of the PDE")
      ->capture_default_str();
  cmd->add_option("--measure", o->measure, "As thickness's --measure: wall, sphere, paper")
      ->capture_default_str();
  cmd->add_option("--edges", o->edges, "As thickness's --edges: wall, exact")
      ->capture_default_str();
  cmd->add_option("--max-thickness", o->max_thickness,
                  "Also list each part's regions thicker than this (in its report)");
  cmd->add_option("--min-region-area", o->min_region_area,
                  "The speck area (default: h0^2/4, at most 0.1 % of the part's area): smaller thin "
                  "regions are listed apart, but the verdict counts every thin face");
  add_solver_mesh_options(*cmd, o->max_edge, o->sharp_angle);
  add_solver_choice_options(*cmd, o->solver);
  cmd->add_option_function<std::string>(
         "--max-memory",
         [o](const std::string& text) {
           o->max_memory_bytes = parse_memory_size(text, "--max-memory");
         },
         "Memory limit of each part: MB, or with a unit, e.g. 800MB, 2G (default: the "
         "machine's memory divided among the jobs)")
      ->type_name("SIZE");
  cmd->add_flag("--fit-memory", o->fit_memory,
                "As thickness's --fit-memory: a part whose solver mesh does not fit its memory "
                "limit is solved on the coarser mesh predicted to fit");
  cmd->callback([o, &exit_code] { run_check_all(*o, exit_code); });
}

}  // namespace bemshape::apps
