#pragma once
// Memory accounting for large allocations: how much the machine can give, how much this
// process has used at its peak, and a guard that refuses an allocation that would not fit
// with a message naming what to do instead (instead of an out-of-memory kill). The budget
// is the smallest of: the usable part of the machine's available memory, of what the
// process's cgroup may still take, of the address space left under `ulimit -v`, and
// --max-memory. core/memory_watch.hpp holds the running account of a whole run.

#include <sys/resource.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "core/errors.hpp"

namespace bemshape {

/// Bytes the kernel reports as available for new allocations (MemAvailable in
/// /proc/meminfo); 0 if unknown.
inline std::uint64_t available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t value = 0;
  std::string unit;
  while (meminfo >> key >> value >> unit)
    if (key == "MemAvailable:") return value * 1024;
  return 0;
}

/// Peak resident set size of this process (VmHWM in /proc/self/status) in bytes; 0 if unknown.
inline std::uint64_t peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) {
      std::istringstream fields(line.substr(6));
      std::uint64_t kb = 0;
      fields >> kb;
      return kb * 1024;
    }
  }
  return 0;
}

/// Bytes this process may still map under its address-space limit (RLIMIT_AS, `ulimit -v`):
/// the limit minus the current virtual size (VmSize); 0 if there is no limit, 1 if the limit
/// is already used up.
inline std::uint64_t address_space_left_bytes() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0;
  std::ifstream status("/proc/self/status");
  std::string line;
  std::uint64_t used = 0;
  while (std::getline(status, line))
    if (line.rfind("VmSize:", 0) == 0) {
      std::istringstream fields(line.substr(7));
      fields >> used;
      used *= 1024;
      break;
    }
  const auto cap = static_cast<std::uint64_t>(limit.rlim_cur);
  return cap > used ? cap - used : 1;
}

/// Bytes the process's cgroup may still take (memory.max − memory.current, cgroup v2, or
/// memory.limit_in_bytes − memory.usage_in_bytes, v1); 0 if unlimited or unknown.
inline std::uint64_t cgroup_memory_left_bytes() {
  const auto read = [](const char* path) -> std::uint64_t {
    std::ifstream in(path);
    std::string text;
    if (!(in >> text) || text == "max") return 0;
    const unsigned long long v = std::strtoull(text.c_str(), nullptr, 10);
    return v >= (1ull << 60) ? 0 : v;  // v1 writes "unlimited" as about 2^63
  };
  for (const auto& [limit_path, usage_path] :
       {std::pair{"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current"},
        std::pair{"/sys/fs/cgroup/memory/memory.limit_in_bytes",
                  "/sys/fs/cgroup/memory/memory.usage_in_bytes"}}) {
    const std::uint64_t limit = read(limit_path);
    if (limit == 0) continue;
    const std::uint64_t used = read(usage_path);
    return limit > used ? limit - used : 1;
  }
  return 0;
}

/// Fraction of the available memory one allocation may claim: the rest is left for the
/// operating system, the other arrays of the run and the file cache.
inline constexpr double kUsableMemoryFraction = 0.8;

/// Bytes one large allocation may claim: the usable part of the available memory
/// (kUsableMemoryFraction of MemAvailable), capped by the address space left under
/// `ulimit -v` and by `limit_bytes` (--max-memory) when non-zero; 0 if nothing is known.
inline std::uint64_t memory_budget_bytes(std::uint64_t limit_bytes = 0) {
  std::uint64_t budget = limit_bytes;
  const auto cap = [&budget](std::uint64_t bytes) {
    if (bytes > 0) budget = budget == 0 ? bytes : std::min(budget, bytes);
  };
  const std::uint64_t available = available_memory_bytes();
  if (available > 0) cap(static_cast<std::uint64_t>(kUsableMemoryFraction * double(available)));
  const std::uint64_t cgroup = cgroup_memory_left_bytes();
  if (cgroup > 0) cap(static_cast<std::uint64_t>(kUsableMemoryFraction * double(cgroup)));
  const std::uint64_t address_space = address_space_left_bytes();
  if (address_space > 0)
    cap(static_cast<std::uint64_t>(kUsableMemoryFraction * double(address_space)));
  return budget;
}

/// What sets memory_budget_bytes(limit_bytes), for messages: " (--max-memory)",
/// " (ulimit -v)", " (cgroup)" or "" (the machine's available memory).
inline std::string memory_budget_reason(std::uint64_t limit_bytes = 0) {
  const std::uint64_t budget = memory_budget_bytes(limit_bytes);
  if (limit_bytes > 0 && budget == limit_bytes) return " (--max-memory)";
  const std::uint64_t address_space = address_space_left_bytes();
  if (address_space > 0 &&
      budget == static_cast<std::uint64_t>(kUsableMemoryFraction * double(address_space)))
    return " (ulimit -v)";
  const std::uint64_t cgroup = cgroup_memory_left_bytes();
  if (cgroup > 0 && budget == static_cast<std::uint64_t>(kUsableMemoryFraction * double(cgroup)))
    return " (cgroup)";
  return "";
}

/// Throws ResourceError if `bytes` exceed memory_budget_bytes(limit_bytes). `what` names the
/// allocation, `instead` says what the user can do. The message names the binding limit
/// (memory_budget_reason).
inline void require_memory(std::uint64_t bytes, const std::string& what, const std::string& instead,
                           std::uint64_t limit_bytes = 0) {
  const std::uint64_t budget = memory_budget_bytes(limit_bytes);
  if (budget == 0 || bytes <= budget) return;
  std::ostringstream msg;
  msg.precision(3);
  msg << what << " needs " << double(bytes) / 1e9 << " GB but only " << double(budget) / 1e9
      << " GB may be used";
  msg << memory_budget_reason(limit_bytes) << "; " << instead;
  throw ResourceError(msg.str());
}

}  // namespace bemshape
