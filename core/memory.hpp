#pragma once
// Memory accounting for large allocations: how much the machine can give, how much this
// process has used at its peak, and a guard that refuses an allocation that would not fit
// with a message naming what to do instead (instead of an out-of-memory kill).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

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

/// Fraction of the available memory one allocation may claim: the rest is left for the
/// operating system, the other arrays of the run and the file cache.
inline constexpr double kUsableMemoryFraction = 0.8;

/// Throws ResourceError if `bytes` exceed `limit_bytes` (when non-zero) or the usable part of
/// the available memory. `what` names the allocation, `instead` says what the user can do.
inline void require_memory(std::uint64_t bytes, const std::string& what, const std::string& instead,
                           std::uint64_t limit_bytes = 0) {
  const std::uint64_t available = available_memory_bytes();
  std::uint64_t budget = limit_bytes;
  if (available > 0) {
    const auto usable = static_cast<std::uint64_t>(kUsableMemoryFraction * double(available));
    budget = budget == 0 ? usable : std::min(budget, usable);
  }
  if (budget == 0 || bytes <= budget) return;
  std::ostringstream msg;
  msg.precision(3);
  msg << what << " needs " << double(bytes) / 1e9 << " GB but only " << double(budget) / 1e9
      << " GB may be used";
  if (limit_bytes > 0 && limit_bytes == budget) msg << " (--max-memory)";
  msg << "; " << instead;
  throw ResourceError(msg.str());
}

}  // namespace bemshape
