// Progress of long work done by several threads, read by another (a console monitor): `done` of `total` units.
// Workers add to `done` in coarse steps (a few thousand per second at most, so the atomic costs nothing).
#pragma once
#include <atomic>
#include <cstdint>

namespace torte {

struct ProgressCounter {
  std::atomic<uint64_t> done{0};
  std::atomic<uint64_t> total{0};
  void add(uint64_t units) { done.fetch_add(units, std::memory_order_relaxed); }
};

}  // namespace torte
