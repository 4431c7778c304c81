// Memory for the large read-mostly arrays a traversal walks at random (BVH nodes, leaf triangles): blocks of
// 2 MiB and more come from their own 2 MiB-aligned mapping marked for transparent huge pages (MADV_HUGEPAGE).
//
// Why: a diffuse ray on a mesh of millions of triangles touches a dozen cache lines spread over tens of MB. With
// 4 KiB pages nearly every one of them is also a TLB miss (Zen 3's 2,048-entry L2 TLB covers 8 MB), and the page
// walk adds to the DRAM latency the ray already waits on; a 2 MiB page covers 512 times as much. Embree advises
// its BVH memory the same way. On a kernel whose THP mode is "madvise" (Debian's default) nothing else gets huge
// pages; with "never" the advice is ignored and the arrays are ordinary pages. Measured (embree-compare, diffuse
// rays, alternating runs, 2026-11-22): bunny-1m 0.95 -> 1.00 of Embree, bunny-4m 0.83-0.90 -> 0.92-1.00.
// TORTE_NO_HUGE_PAGES=1 in the environment leaves out the advice, TORTE_NO_BLOCK_CACHE=1 the reuse of freed
// blocks (deallocate), for A/B runs.
#pragma once
#include <cstddef>
#include <new>
#include <vector>

namespace torte {

namespace huge_pages {
constexpr size_t kHugePage = size_t(2) << 20;
// `bytes` (> 0) of memory aligned to kHugePage when bytes >= kHugePage, else to `align`.
// Throws std::bad_alloc when the system has no memory left.
void* allocate(size_t bytes, size_t align);
// Frees memory from allocate(bytes, align) with the same bytes and align. A block of kHugePage or more is kept
// for reuse by later allocations (at most a quarter of the machine's memory) until release_cached().
void deallocate(void* p, size_t bytes, size_t align) noexcept;
/// Returns every kept block to the system. Called when a scene's build is done: what it freed is not needed again.
void release_cached() noexcept;
/// Bytes of freed blocks kept for reuse (for tests and diagnostics).
size_t cached_bytes() noexcept;
// Bytes of `p`'s mapping backed by huge pages (from /proc/self/smaps), for tests and diagnostics; 0 when unknown.
size_t backed_bytes(const void* p);
// Faults the pages of a fresh block from allocate(bytes, ...) in from all threads (TBB), writing zeros, which a
// fresh mapping holds anyway; does nothing below 32 MiB. Why: a block's first writes take one page fault per
// page (per 2 MiB with huge pages), and a serial writer such as std::vector's zero fill takes them all on one
// thread. On this VM the first touch of memory the host has not backed yet costs about 3.5 s per GiB on one
// thread and half that on two (the kernel clears each page while the host maps it); a 28 M-triangle scene
// touches 4-5 GB while it builds.
void fault_in(void* p, size_t bytes);
}  // namespace huge_pages

// Standard allocator over huge_pages::allocate, for std::vector.
template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
  T* allocate(size_t n) {
    if (n > size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(huge_pages::allocate(n * sizeof(T), alignof(T)));
  }
  void deallocate(T* p, size_t n) noexcept { huge_pages::deallocate(p, n * sizeof(T), alignof(T)); }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

// n value-initialised elements, whose pages all threads faulted in before the (serial) initialisation: for
// large arrays that will be written in full.
template <class T>
HugePageVector<T> make_huge_page_vector(size_t n) {
  HugePageVector<T> v;
  v.reserve(n);
  if (n > 0) huge_pages::fault_in(v.data(), n * sizeof(T));
  v.resize(n);
  return v;
}

/// Frees a vector's storage. `v = {}` does not: it picks the initializer-list assignment, which only clears and
/// keeps the capacity (the BVH build's 32 B/tri references stayed resident that way).
template <class V>
void free_storage(V& v) {
  V().swap(v);
}

}  // namespace torte
