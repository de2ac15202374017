#pragma once
// The running account of a run's memory: what the process actually holds, watched while it
// assembles and solves, so that a run whose estimate was too low stops cleanly with a
// ResourceError (exit code 2, one line naming the size and a way out) instead of being
// killed by the kernel's OOM killer or failing an allocation inside a parallel loop.
//
// A MemoryWatch starts a thread that samples, every kSamplePeriod:
//   • the process's resident size (VmRSS, /proc/self/statm), against the run's limit: the
//     resident size when the watch started plus kUsableMemoryFraction of the memory the
//     machine had available then (MemAvailable) and of what the cgroup allowed
//     (memory.max − memory.current), capped by --max-memory (a limit on the whole process);
//   • the machine's available memory now, against a reserve (kMemoryReserveFraction of
//     MemTotal): other programs may grow while the run does, and the OOM killer picks the
//     largest process;
//   • the virtual size (VmSize, /proc/self/statm) against kAddressSpaceFraction of `ulimit
//     -v` (RLIMIT_AS): there the kernel refuses mappings, and allocations fail.
// The first overrun is recorded once (detail::memory_overrun in core/cancellation.hpp) and
// the run stops at its next poll point (cancellation_requested(), throw_if_cancelled():
// every block, row, point or iteration of the long loops), as it does for --timeout.
//
// The watch is process-wide, like the cancellation state: one run per process. Nested
// watches share the first one's limit. Stages set what the message names and suggests
// (set_memory_context) before they allocate.

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>

#include "core/cancellation.hpp"
#include "core/memory.hpp"
#include "core/number_text.hpp"

namespace bemshape {

/// Period of the watch's samples: at the assembly's rate of growth (under 1 GB/s on the 2
/// cores of docs/benchmarks.md) a run grows by less than 25 MB between two samples, far
/// inside the fifth of the available memory the limit leaves free.
inline constexpr std::chrono::milliseconds kMemorySamplePeriod{25};

/// The machine's available memory below which the watch stops the run, as a fraction of
/// MemTotal: the kernel's OOM killer acts near zero; 3 % (740 MB on a 24 GB machine) leaves
/// room for the rest of the stage that is running when the sample is taken.
inline constexpr double kMemoryReserveFraction = 0.03;

/// The fraction of `ulimit -v` the virtual size may reach: beyond it, one more heap arena or
/// block of factors could fail to map.
inline constexpr double kAddressSpaceFraction = 0.95;

/// Resident and virtual size of this process [bytes] (/proc/self/statm); zeros if unknown.
struct ProcessMemory {
  std::uint64_t resident = 0;
  std::uint64_t virtual_size = 0;
};

inline ProcessMemory process_memory() {
  ProcessMemory m;
  if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
    unsigned long long pages = 0, resident = 0;
    if (std::fscanf(f, "%llu %llu", &pages, &resident) == 2) {
      const auto page = static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
      m.virtual_size = pages * page;
      m.resident = resident * page;
    }
    std::fclose(f);
  }
  return m;
}

/// MemTotal in /proc/meminfo [bytes]; 0 if unknown.
inline std::uint64_t total_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  std::uint64_t value = 0;
  while (meminfo >> key >> value >> unit)
    if (key == "MemTotal:") return value * 1024;
  return 0;
}

namespace detail {

/// The watch's state; one per process.
struct MemoryWatchState {
  std::mutex mutex;
  std::condition_variable wake;
  std::thread thread;
  int users = 0;
  bool stop = false;
  std::uint64_t resident_limit = 0;  ///< 0: none
  std::string resident_limit_reason;  ///< " (--max-memory)", "" (the machine), " (cgroup)"
  std::uint64_t address_space_limit = 0;  ///< 0: none
  std::uint64_t reserve = 0;              ///< MemAvailable below which the run stops
  std::uint64_t start_resident = 0;
  std::atomic<std::uint64_t> peak_resident{0};  ///< the largest sample
  std::string what = "the run";   ///< what is being built, for the message
  std::string instead = "use a coarser mesh (larger --max-edge) or raise --max-memory";
};

inline MemoryWatchState& memory_watch_state() {
  static MemoryWatchState state;
  return state;
}

/// Records the first overrun: the message for throw_if_cancelled() and the flag.
inline void record_memory_overrun(MemoryWatchState& s, const std::string& why) {
  std::lock_guard<std::mutex> lock(memory_overrun_mutex());
  if (memory_overrun.load()) return;
  memory_overrun_message() = s.what + ": " + why + "; stopped cleanly, no output file was " +
                             "written or changed; " + s.instead;
  memory_overrun.store(true);
}

inline void watch_memory(MemoryWatchState& s) {
  const std::uint64_t gb = 1000ull * 1000ull * 1000ull;
  const auto text = [gb](std::uint64_t bytes) { return number_text(double(bytes) / double(gb), 3); };
  std::unique_lock<std::mutex> lock(s.mutex);
  int tick = 0;
  while (!s.stop) {
    const ProcessMemory m = process_memory();
    std::uint64_t peak = s.peak_resident.load();
    while (m.resident > peak && !s.peak_resident.compare_exchange_weak(peak, m.resident)) {}
    if (s.resident_limit > 0 && m.resident > s.resident_limit)
      record_memory_overrun(s, "the process holds " + text(m.resident) + " GB, more than the " +
                                   text(s.resident_limit) + " GB it may use" +
                                   s.resident_limit_reason);
    if (s.address_space_limit > 0 && m.virtual_size > s.address_space_limit)
      record_memory_overrun(s, "the process maps " + text(m.virtual_size) +
                                   " GB of address space, near the limit of " +
                                   text(std::uint64_t(double(s.address_space_limit) /
                                                      kAddressSpaceFraction)) +
                                   " GB (ulimit -v)");
    // MemAvailable is a file read and a parse: every fourth sample.
    if (s.reserve > 0 && ++tick % 4 == 0) {
      const std::uint64_t available = available_memory_bytes();
      if (available > 0 && available < s.reserve)
        record_memory_overrun(s, "the machine's available memory fell to " + text(available) +
                                     " GB while the process held " + text(m.resident) +
                                     " GB (other programs took the rest)");
    }
    s.wake.wait_for(lock, kMemorySamplePeriod);
  }
}

}  // namespace detail

/// Sets what an overrun's message names (`what`, e.g. "part.stl: the hierarchical-matrix BEM
/// system of 766244 faces (estimated 15.4 GB)") and suggests (`instead`).
inline void set_memory_context(const std::string& what, const std::string& instead) {
  detail::MemoryWatchState& s = detail::memory_watch_state();
  std::lock_guard<std::mutex> lock(s.mutex);
  s.what = what;
  s.instead = instead;
}

/// The largest resident size the watch has seen [bytes] (0 before any watch ran).
inline std::uint64_t watched_peak_resident_bytes() {
  return detail::memory_watch_state().peak_resident.load();
}

/// The resident size the run may reach [bytes], as a MemoryWatch started now would set it;
/// 0 if nothing is known. `reason` receives what sets it: " (--max-memory)", " (ulimit -v)",
/// " (cgroup)" or "" (the machine's available memory).
inline std::uint64_t resident_memory_limit_bytes(std::uint64_t max_memory_bytes,
                                                 std::string* reason = nullptr) {
  const std::uint64_t resident = process_memory().resident;
  std::uint64_t limit = 0;
  std::string why;
  const auto cap = [&](std::uint64_t bytes, const char* because) {
    if (bytes > 0 && (limit == 0 || bytes < limit)) {
      limit = bytes;
      why = because;
    }
  };
  if (const std::uint64_t available = available_memory_bytes(); available > 0)
    cap(resident + std::uint64_t(kUsableMemoryFraction * double(available)), "");
  if (const std::uint64_t cgroup = cgroup_memory_left_bytes(); cgroup > 0)
    cap(resident + std::uint64_t(kUsableMemoryFraction * double(cgroup)), " (cgroup)");
  // Under `ulimit -v` the mappings count, not the resident pages: the resident size may
  // grow by what is left of the address space (thread stacks and heap arenas are mapped
  // but mostly not resident).
  if (const std::uint64_t address_space = address_space_left_bytes(); address_space > 0)
    cap(resident + std::uint64_t(kUsableMemoryFraction * double(address_space)), " (ulimit -v)");
  cap(max_memory_bytes, " (--max-memory)");
  if (reason) *reason = why;
  return limit;
}

/// For a parallel loop that caught std::bad_alloc (an exception cannot leave an OpenMP
/// region): records it as the run's memory overrun, so that the loop's other iterations are
/// skipped (cancellation_requested()) and throw_if_cancelled() after the loop throws a
/// ResourceError naming the process's size. Thread-safe; the first overrun is kept.
inline void note_failed_allocation() {
  detail::MemoryWatchState& s = detail::memory_watch_state();
  const ProcessMemory m = process_memory();
  const auto gb = [](std::uint64_t bytes) { return number_text(double(bytes) / 1e9, 3); };
  std::string what, instead;
  {
    std::lock_guard<std::mutex> lock(s.mutex);
    what = s.what;
    instead = s.instead;
  }
  std::lock_guard<std::mutex> lock(detail::memory_overrun_mutex());
  if (detail::memory_overrun.load()) return;
  detail::memory_overrun_message() =
      what + ": an allocation failed with the process holding " + gb(m.resident) +
      " GB and mapping " + gb(m.virtual_size) +
      " GB; stopped cleanly, no output file was written or changed; " + instead;
  detail::memory_overrun.store(true);
}

/// Watches the process's memory for as long as it lives (see the top of this file).
/// `max_memory_bytes`: --max-memory, 0 for none. The environment variable
/// BEMSHAPE_TEST_RESIDENT_LIMIT (bytes) replaces the resident limit of the watch alone, not
/// that of the estimates: the tests use it to check the watch's stop on a real assembly.
class MemoryWatch {
 public:
  explicit MemoryWatch(std::uint64_t max_memory_bytes) {
    detail::MemoryWatchState& s = detail::memory_watch_state();
    std::lock_guard<std::mutex> lock(s.mutex);
    if (s.users++ > 0) return;
    s.stop = false;
    s.start_resident = process_memory().resident;
    s.peak_resident.store(s.start_resident);
    s.resident_limit = resident_memory_limit_bytes(max_memory_bytes, &s.resident_limit_reason);
    if (const char* test_limit = std::getenv("BEMSHAPE_TEST_RESIDENT_LIMIT")) {
      s.resident_limit = std::strtoull(test_limit, nullptr, 10);
      s.resident_limit_reason = " (BEMSHAPE_TEST_RESIDENT_LIMIT)";
    }
    rlimit as{};
    s.address_space_limit =
        ::getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY
            ? std::uint64_t(kAddressSpaceFraction * double(as.rlim_cur))
            : 0;
    s.reserve = std::uint64_t(kMemoryReserveFraction * double(total_memory_bytes()));
    s.thread = std::thread(detail::watch_memory, std::ref(s));
  }
  ~MemoryWatch() {
    detail::MemoryWatchState& s = detail::memory_watch_state();
    std::thread finished;
    {
      std::lock_guard<std::mutex> lock(s.mutex);
      if (--s.users > 0) return;
      s.stop = true;
      finished = std::move(s.thread);
    }
    s.wake.notify_all();
    if (finished.joinable()) finished.join();
  }
  MemoryWatch(const MemoryWatch&) = delete;
  MemoryWatch& operator=(const MemoryWatch&) = delete;
};

}  // namespace bemshape
