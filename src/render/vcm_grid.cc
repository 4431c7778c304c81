#include "render/vcm_grid.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/parallel.h"

namespace torte {

uint32_t PhotonGrid::bucket(int x, int y, int z) const {
  // Teschner et al.'s spatial hash.
  return (uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u ^ uint32_t(z) * 83492791u) & mask_;
}

int PhotonGrid::neighbour_buckets(Vec3f p, uint32_t out[8]) const {
  const float q[3] = {p.x * inv_cell_, p.y * inv_cell_, p.z * inv_cell_};
  int c[3], o[3];
  for (int a = 0; a < 3; ++a) {
    const float f = std::floor(q[a]);
    c[a] = int(f);
    o[a] = q[a] - f < 0.5f ? c[a] - 1 : c[a] + 1;  // the neighbour on the side of the cell p is nearer to
  }
  int n = 0;
  for (int k = 0; k < 8; ++k) {
    const uint32_t b = bucket(k & 1 ? o[0] : c[0], k & 2 ? o[1] : c[1], k & 4 ? o[2] : c[2]);
    if (std::find(out, out + n, b) == out + n) out[n++] = b;  // two cells sharing a bucket: visit it once
  }
  std::sort(out, out + n);
  return n;
}

void PhotonGrid::build(std::span<const Vec3f> points, float r) {
  radius_ = r;
  inv_cell_ = 1 / (2 * r);
  const size_t n = points.size();
  const uint32_t buckets = std::bit_ceil(uint32_t(std::max<size_t>(n, 1)));
  mask_ = buckets - 1;
  keys_.resize(n);
  parallel_for_blocks(size_t(0), n, 4096, [&](IndexRange<size_t> range) {
    for (size_t k = range.begin(); k != range.end(); ++k) {
      const Vec3f p = points[k];
      const uint32_t b = bucket(int(std::floor(p.x * inv_cell_)), int(std::floor(p.y * inv_cell_)),
                                int(std::floor(p.z * inv_cell_)));
      keys_[k] = (uint64_t(b) << 32) | uint64_t(k);
    }
  });
  // Keys are distinct, so the order (and so every query's visiting order) does not depend on the split.
  parallel_sort(keys_.begin(), keys_.end(), [](uint64_t a, uint64_t b) { return a < b; });
  begin_.assign(buckets, 0);
  end_.assign(buckets, 0);
  parallel_for_blocks(size_t(0), n, 4096, [&](IndexRange<size_t> range) {
    for (size_t i = range.begin(); i != range.end(); ++i) {
      const uint32_t b = uint32_t(keys_[i] >> 32);
      if (i == 0 || uint32_t(keys_[i - 1] >> 32) != b) begin_[b] = uint32_t(i);
      if (i + 1 == n || uint32_t(keys_[i + 1] >> 32) != b) end_[b] = uint32_t(i + 1);
    }
  });
}

}  // namespace torte
