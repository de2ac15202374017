#pragma once
// Keeping freed memory in the process for reuse, for programs that allocate and free
// block-sized temporaries many times: the H-matrix assembly does so millions of times per
// thread (cross approximation factors, QR workspaces, 10 kB to a few MB each).
//
// With glibc's defaults, free memory at the top of a heap goes back to the kernel once it
// exceeds the trim threshold, and requests above the mmap threshold (raised dynamically up
// to 32 MB) get fresh mappings. Either way the next request is served by zero-filled pages
// through page faults, one per 4 kB page, which cost about 10 µs each on the virtual
// machines of docs/benchmarks.md. retain_freed_heap_memory() serves requests up to 32 MB
// from the heaps and keeps freed memory there (trim threshold 2 GiB). On the 102096-face
// hollow box (`bemshape thickness`, docs/benchmarks.md) the page faults went from 1.35 to
// 0.98 million (about the operators' own first touches), the system time from 12.7 to
// 10.2 s and the run from 76.8 to 72.5 s, with the same peak (3.92 GB): what is freed is
// reused by the next blocks, and the large long-lived arrays are allocated once.
//
// A process-wide setting, so it is the executables' choice (apps/main.cpp, bench/), called
// once before anything is allocated; a no-op with other C libraries.

#include <climits>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace bemshape {

inline void retain_freed_heap_memory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);  // glibc's largest allowed value on 64-bit
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
}

}  // namespace bemshape
