#pragma once
// Wall time of each stage of a run, in order: what the library's jobs return with their
// results (analysis/measure_thickness.hpp, …) and the reports print in their "timing"
// sections.

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace bemshape::analysis {

class StageTimes {
 public:
  using Clock = std::chrono::steady_clock;

  /// Runs `work()`, adds its wall time [s] to `stage` and returns what it returns.
  template <class Work>
  auto time(const std::string& stage, Work&& work) {
    const auto start = Clock::now();
    struct Record {
      StageTimes& times;
      const std::string& stage;
      Clock::time_point start;
      ~Record() { times.add(stage, std::chrono::duration<double>(Clock::now() - start).count()); }
    } record{*this, stage, start};
    return work();
  }
  /// Adds `seconds` to `stage` (appended if new).
  void add(const std::string& stage, double seconds) {
    for (auto& [name, total] : stages_)
      if (name == stage) {
        total += seconds;
        return;
      }
    stages_.emplace_back(stage, seconds);
  }
  /// Adds every stage of `other`, in its order.
  void add(const StageTimes& other) {
    for (const auto& [name, seconds] : other.stages())
      add(name, seconds);
  }
  const std::vector<std::pair<std::string, double>>& stages() const { return stages_; }
  /// Seconds since construction.
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

 private:
  Clock::time_point start_ = Clock::now();
  std::vector<std::pair<std::string, double>> stages_;
};

}  // namespace bemshape::analysis
