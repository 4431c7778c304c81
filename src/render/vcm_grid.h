// VCM's photon lookup (render/integrator_vcm.h): a hashed uniform grid over the light-subpath vertices of one
// iteration, cells 2r wide, so every point within r of a query lies in the 2x2x2 cells nearest to it. Built in
// parallel (keys computed per photon, one parallel sort by (bucket, photon)), so the photons of a bucket come
// in photon order whatever the thread count: a query visits them in a fixed order.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/vec.h"

namespace torte {

class PhotonGrid {
 public:
  /// Rebuilds the grid over `points` (photon k at points[k]) for lookups of radius r > 0.
  void build(std::span<const Vec3f> points, float r);

  /// Calls fn(k) for every photon k within the radius of p (distance strictly below r), in a fixed order:
  /// buckets ascending, photons ascending within a bucket.
  template <class Fn>
  void query(Vec3f p, std::span<const Vec3f> points, Fn&& fn) const {
    if (keys_.empty()) return;
    uint32_t buckets[8];
    const int n = neighbour_buckets(p, buckets);
    const float r2 = radius_ * radius_;
    for (int b = 0; b < n; ++b)
      for (uint32_t i = begin_[buckets[b]], e = end_[buckets[b]]; i < e; ++i) {
        const uint32_t k = uint32_t(keys_[i]);
        const Vec3f d = points[k] - p;
        if (dot(d, d) < r2) fn(k);
      }
  }

  size_t memory_bytes() const { return keys_.capacity() * 8 + (begin_.capacity() + end_.capacity()) * 4; }

 private:
  uint32_t bucket(int x, int y, int z) const;
  // The distinct buckets of the 8 cells nearest to p, ascending; returns their count.
  int neighbour_buckets(Vec3f p, uint32_t out[8]) const;

  float radius_ = 0, inv_cell_ = 0;
  uint32_t mask_ = 0;              // bucket count - 1 (a power of two)
  std::vector<uint64_t> keys_;     // (bucket << 32) | photon, sorted
  std::vector<uint32_t> begin_, end_;  // by bucket: its range in keys_
};

}  // namespace torte
