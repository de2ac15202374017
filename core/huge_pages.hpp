#pragma once
// Transparent huge pages (2 MB) for the heap. A large run's memory is a few GB of operator
// blocks, each written once when it is assembled; with 4 kB pages every one of those pages
// costs a page fault (about 10 µs on the virtual machines of docs/benchmarks.md), with 2 MB
// pages one fault in 512 does.
//
// Where the kernel's THP mode is "madvise" (/sys/kernel/mm/transparent_hugepage/enabled; the
// default of Debian's kernels and of many cloud images) only memory marked with
// madvise(MADV_HUGEPAGE) gets huge pages. glibc (2.35 and later) marks its heaps and its large
// mappings so when the tunable glibc.malloc.hugetlb=1 is set, and it reads GLIBC_TUNABLES only
// when a process starts. restart_with_heap_huge_pages(argv), called first thing in main,
// therefore sets the tunable and executes the program again (/proc/self/exe, same arguments,
// same environment otherwise). It does nothing
//   - when GLIBC_TUNABLES already names glibc.malloc.hugetlb (the user's choice, or the
//     restarted process itself), so it restarts at most once;
//   - when the kernel's mode is "always" (the heap gets huge pages anyway) or "never";
//   - with other C libraries or older glibc;
//   - if the execution fails: the program then goes on with 4 kB pages.
// Other GLIBC_TUNABLES settings the user made are kept.
//
// Measured on the 102096-face hollow box (`bemshape thickness`, docs/benchmarks.md): page
// faults 1.03 → 0.37 million, system time 11.6 → 6.8 s, run 75.0 → 69.3 s, the same peak
// memory.
//
// The marking reaches only what is mapped read-write when glibc marks it. A worker thread's
// heap (an arena of at most 64 MiB, reserved inaccessible) is made read-write as it grows, by
// as much as each request needs, and with glibc 2.36 only its first part ends up marked (the
// fault counts below say so), so the operator blocks and workspaces of the assembly threads
// kept 4 kB pages: most of the faults left on that box were theirs. pad_heap_growth() sets
// glibc's top pad (M_TOP_PAD) to those 64 MiB, so a new thread heap is made read-write and
// marked whole when it is created, and the main heap grows in the same steps. Nothing is
// committed by that: pages are still taken as they are first written. On the same box, three
// pairs of runs back to back (docs/benchmarks.md, "Heap and huge pages"): page faults 0.34–0.65
// million → about 4500, run 60.2–63.3 s → 48.6–51.8 s, the same peak; the solve's interior
// product took 10.1–12.0 s → 5.5–7.0 s, its blocks now read through huge-page translations.
//
// The executables call both (apps/main.cpp, bench/); the library never does.

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#if defined(__linux__)
#include <unistd.h>
#endif
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace bemshape {

/// The kernel's transparent-huge-page mode, "always", "madvise" or "never" (the bracketed word
/// of /sys/kernel/mm/transparent_hugepage/enabled), or "" where there is none.
inline std::string transparent_huge_page_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  if (!std::getline(in, line)) return "";
  const auto open = line.find('['), close = line.find(']');
  if (open == std::string::npos || close == std::string::npos || close < open) return "";
  return line.substr(open + 1, close - open - 1);
}

/// Whether the process's heap is given huge pages: the kernel's mode is "always", or it is
/// "madvise" and glibc was started with glibc.malloc.hugetlb=1.
inline bool heap_uses_huge_pages() {
  const std::string mode = transparent_huge_page_mode();
  if (mode == "always") return true;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  return mode == "madvise" && tunables != nullptr &&
         std::strstr(tunables, "glibc.malloc.hugetlb=1") != nullptr;
}

/// See the file comment. Returns only when the program goes on in this process.
inline void restart_with_heap_huge_pages(char** argv) {
#if defined(__linux__) && defined(__GLIBC__) && (__GLIBC__ > 2 || __GLIBC_MINOR__ >= 35)
  const char* current = std::getenv("GLIBC_TUNABLES");
  if (current != nullptr && std::strstr(current, "glibc.malloc.hugetlb") != nullptr) return;
  if (transparent_huge_page_mode() != "madvise") return;
  const std::string previous = current != nullptr ? current : "";
  const std::string value =
      "glibc.malloc.hugetlb=1" + (previous.empty() ? std::string() : ":" + previous);
  if (::setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
  ::execv("/proc/self/exe", argv);
  // Still here: the execution failed. Go on as started.
  if (current != nullptr)
    ::setenv("GLIBC_TUNABLES", previous.c_str(), 1);
  else
    ::unsetenv("GLIBC_TUNABLES");
#else
  (void)argv;
#endif
}

/// See the file comment: heaps grow in steps of 64 MiB (glibc's largest thread heap on 64-bit
/// systems), so every thread heap is marked for huge pages whole. Call before the threads
/// start; a no-op with other C libraries.
inline void pad_heap_growth() {
#if defined(__GLIBC__)
  mallopt(M_TOP_PAD, 64 * 1024 * 1024);
#endif
}

}  // namespace bemshape
