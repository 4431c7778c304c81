#include "core/huge_pages.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <vector>

#include "core/parallel.h"

namespace torte::huge_pages {
namespace {

size_t round_up(size_t bytes) { return (bytes + kHugePage - 1) & ~(kHugePage - 1); }
// Blocks below kHugePage come from operator new, with at least its default alignment.
std::align_val_t small_align(size_t align) {
  return std::align_val_t(align > alignof(std::max_align_t) ? align : alignof(std::max_align_t));
}

// A fresh mapping of `size` bytes (a multiple of kHugePage) starting on a 2 MiB boundary: one huge page more is
// mapped and both ends trimmed (a huge page can only back an aligned 2 MiB range).
uintptr_t map_aligned(size_t size) {
  void* const raw = ::mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const uintptr_t start = reinterpret_cast<uintptr_t>(raw);
  const uintptr_t aligned = (start + kHugePage - 1) & ~uintptr_t(kHugePage - 1);
  if (aligned > start) ::munmap(raw, aligned - start);
  const uintptr_t end = start + size + kHugePage;
  if (end > aligned + size) ::munmap(reinterpret_cast<void*>(aligned + size), end - (aligned + size));
  return aligned;
}

void advise(uintptr_t at, size_t size) {
#ifdef MADV_HUGEPAGE
  // Advice only: an error (THP off, an old kernel) leaves ordinary pages.
  if (std::getenv("TORTE_NO_HUGE_PAGES") == nullptr) ::madvise(reinterpret_cast<void*>(at), size, MADV_HUGEPAGE);
#endif
}

// Freed blocks kept for reuse. Why: on the VMs torte runs on, the first touch of memory the host has not backed
// costs about 3.5 s per GiB on one thread (fault_in below), and a 28 M-triangle scene build frees blocks of
// hundreds of MB (the references, the node scratch) shortly before it maps as much again (nodes, leaves). Handing
// the freed pages out again skips those first touches. Only pages that are resident are kept (a block is cut
// after its last resident huge page when freed), and a request no kept block holds gathers several into one
// aligned range (mremap moves pages without copying them), so no kept page waits while fresh ones are touched:
// the resident peak stays what it was. Reused memory is not zeroed: std::vector never relies on that, and
// make_huge_page_vector value-initialises its elements.
struct Block {
  uintptr_t at;
  size_t size;
};
struct Cache {
  std::mutex mutex;
  std::vector<Block> blocks;
  size_t bytes = 0;
  size_t limit = 0;  // a quarter of the machine's memory
  Cache() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    limit = pages > 0 && page > 0 ? size_t(pages) * size_t(page) / 4 : 0;
    if (std::getenv("TORTE_NO_BLOCK_CACHE") != nullptr) limit = 0;
  }
};
Cache& cache() {
  static Cache c;
  return c;
}

// Bytes of [at, at + size) up to and including its last huge page with a resident page (0: none resident, or
// mincore failed).
size_t resident_extent(uintptr_t at, size_t size) {
  const size_t page = size_t(::sysconf(_SC_PAGESIZE));
  std::vector<unsigned char> in(size / page);
  if (::mincore(reinterpret_cast<void*>(at), size, in.data()) != 0) return 0;
  for (size_t i = in.size(); i-- > 0;)
    if (in[i] & 1) return round_up((i + 1) * page);
  return 0;
}

// `size` bytes from the kept blocks (the caller holds the lock), 0 when none are kept: the smallest block that
// holds the request, its tail kept; else an aligned fresh range into which the largest blocks are moved, one
// after another, until it is full or none is left (the rest of the range is fresh).
uintptr_t take_cached(Cache& c, size_t size) {
  if (c.blocks.empty()) return 0;
  size_t best = c.blocks.size();
  for (size_t i = 0; i < c.blocks.size(); ++i)
    if (c.blocks[i].size >= size && (best == c.blocks.size() || c.blocks[i].size < c.blocks[best].size)) best = i;
  if (best < c.blocks.size()) {
    const Block b = c.blocks[best];
    c.blocks.erase(c.blocks.begin() + std::ptrdiff_t(best));
    c.bytes -= size;
    if (b.size > size) c.blocks.push_back({b.at + size, b.size - size});
    return b.at;
  }
  const uintptr_t target = map_aligned(size);
  std::sort(c.blocks.begin(), c.blocks.end(), [](const Block& x, const Block& y) { return x.size < y.size; });
  size_t filled = 0;
  while (filled < size && !c.blocks.empty()) {
    Block& b = c.blocks.back();  // the largest
    const size_t take = std::min(b.size, size - filled);
    if (::mremap(reinterpret_cast<void*>(b.at), take, take, MREMAP_MAYMOVE | MREMAP_FIXED,
                 reinterpret_cast<void*>(target + filled)) == MAP_FAILED)
      break;  // the fresh pages of the range serve instead
    filled += take;
    c.bytes -= take;
    if (take == b.size)
      c.blocks.pop_back();
    else
      b = {b.at + take, b.size - take};
  }
  return target;
}

}  // namespace

void* allocate(size_t bytes, size_t align) {
  if (bytes < kHugePage) return ::operator new(bytes, small_align(align));
  const size_t size = round_up(bytes);
  {
    Cache& c = cache();
    const std::lock_guard<std::mutex> lock(c.mutex);
    if (const uintptr_t at = take_cached(c, size)) {
      advise(at, size);
      return reinterpret_cast<void*>(at);
    }
  }
  const uintptr_t at = map_aligned(size);
  advise(at, size);
  return reinterpret_cast<void*>(at);
}

void deallocate(void* p, size_t bytes, size_t align) noexcept {
  if (p == nullptr) return;
  if (bytes < kHugePage) {
    ::operator delete(p, small_align(align));
    return;
  }
  const uintptr_t at = reinterpret_cast<uintptr_t>(p);
  const size_t size = round_up(bytes);
  size_t keep = 0;
  try {
    keep = resident_extent(at, size);
  } catch (...) {  // no memory for mincore's vector: keep nothing
  }
  if (keep < size) ::munmap(reinterpret_cast<void*>(at + keep), size - keep);
  if (keep == 0) return;
  Cache& c = cache();
  {
    const std::lock_guard<std::mutex> lock(c.mutex);
    if (c.bytes + keep <= c.limit) {
      try {
        c.blocks.push_back({at, keep});
        c.bytes += keep;
        return;
      } catch (...) {  // no memory for the list: free the block instead
      }
    }
  }
  ::munmap(p, keep);
}

void release_cached() noexcept {
  Cache& c = cache();
  const std::lock_guard<std::mutex> lock(c.mutex);
  for (const Block& b : c.blocks) ::munmap(reinterpret_cast<void*>(b.at), b.size);
  c.blocks.clear();
  c.bytes = 0;
}

size_t cached_bytes() noexcept {
  Cache& c = cache();
  const std::lock_guard<std::mutex> lock(c.mutex);
  return c.bytes;
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
