#include "core/huge_pages.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "core/parallel.h"

namespace torte::huge_pages {
namespace {

size_t round_up(size_t bytes) { return (bytes + kHugePage - 1) & ~(kHugePage - 1); }
// Blocks below kHugePage come from operator new, with at least its default alignment.
std::align_val_t small_align(size_t align) {
  return std::align_val_t(align > alignof(std::max_align_t) ? align : alignof(std::max_align_t));
}

}  // namespace

void* allocate(size_t bytes, size_t align) {
  if (bytes < kHugePage) return ::operator new(bytes, small_align(align));
  // Map one huge page more than needed and trim both ends, so the block starts on a 2 MiB boundary (a huge page
  // can only back an aligned 2 MiB range).
  const size_t size = round_up(bytes);
  void* const raw = ::mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const uintptr_t start = reinterpret_cast<uintptr_t>(raw);
  const uintptr_t aligned = (start + kHugePage - 1) & ~uintptr_t(kHugePage - 1);
  if (aligned > start) ::munmap(raw, aligned - start);
  const uintptr_t end = start + size + kHugePage;
  if (end > aligned + size) ::munmap(reinterpret_cast<void*>(aligned + size), end - (aligned + size));
  void* const p = reinterpret_cast<void*>(aligned);
#ifdef MADV_HUGEPAGE
  // Advice only: an error (THP off, an old kernel) leaves ordinary pages.
  if (std::getenv("TORTE_NO_HUGE_PAGES") == nullptr) ::madvise(p, size, MADV_HUGEPAGE);
#endif
  return p;
}

void deallocate(void* p, size_t bytes, size_t align) noexcept {
  if (p == nullptr) return;
  if (bytes < kHugePage) {
    ::operator delete(p, small_align(align));
    return;
  }
  ::munmap(p, round_up(bytes));
}

void fault_in(void* p, size_t bytes) {
  constexpr size_t kMinBytes = size_t(32) << 20, kPage = 4096;
  if (p == nullptr || bytes < kMinBytes) return;
  char* const base = static_cast<char*>(p);
  // Chunks of whole huge pages; within them every 4 KiB page is written, so ordinary pages (no huge-page advice)
  // are faulted in too, and with huge pages the first write of each 2 MiB maps it and the rest find it mapped.
  parallel_for_blocks(size_t(0), (bytes + kHugePage - 1) / kHugePage, 1, [&](IndexRange<size_t> r) {
    const size_t end = std::min(bytes, r.end() * kHugePage);
    for (size_t at = r.begin() * kHugePage; at < end; at += kPage) *static_cast<volatile char*>(base + at) = 0;
  });
}

size_t backed_bytes(const void* p) {
  FILE* f = std::fopen("/proc/self/smaps", "r");
  if (f == nullptr) return 0;
  const uintptr_t a = reinterpret_cast<uintptr_t>(p);
  char line[512];
  bool inside = false;
  size_t kib = 0;
  while (std::fgets(line, sizeof line, f) != nullptr) {
    unsigned long lo, hi;
    // Mapping header lines start "lo-hi perms ..." in hex; the fields of a mapping follow it.
    // (field lines such as "AnonHugePages:" stop the scan after one field).
    if (std::sscanf(line, "%lx-%lx", &lo, &hi) == 2) {
      inside = a >= lo && a < hi;
      continue;
    }
    if (inside && std::sscanf(line, "AnonHugePages: %zu kB", &kib) == 1) break;
  }
  std::fclose(f);
  return inside ? kib * 1024 : 0;
}

}  // namespace torte::huge_pages
