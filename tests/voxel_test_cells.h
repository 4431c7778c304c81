// Shared by the voxel tests and the voxel benchmark: a unit-cell handler (id -1 is a bottom slab, other negative
// ids are empty; the traversal's cell callback interface, voxel/voxel_traverse.h) and test grids.
#pragma once
#include <algorithm>
#include <utility>

#include <cmath>
#include <cstdint>

#include "core/rng.h"
#include "voxel/voxel_grid.h"
#include "voxel/voxel_traverse.h"

namespace torte::test {

// Cell handler for tests: id -1 is a bottom slab [0,1] x [0,0.5] x [0,1], other negative ids are empty.
struct SlabCells {
  static bool slab(const Ray& r, float* t_hit) {
    float t0 = 0, t1 = r.t_max;
    const float hi[3] = {1, 0.5f, 1};
    for (int a = 0; a < 3; ++a) {
      if (r.d[a] == 0) {
        if (r.o[a] < 0 || r.o[a] > hi[a]) return false;
        continue;
      }
      float tn = (0 - r.o[a]) / r.d[a], tf = (hi[a] - r.o[a]) / r.d[a];
      if (tn > tf) std::swap(tn, tf);
      t0 = std::max(t0, tn);
      t1 = std::min(t1, tf);
    }
    if (t0 > t1) return false;
    *t_hit = t0;
    return true;
  }
  bool intersect(int16_t id, const Ray& r, Hit* h) const {
    float t;
    if (id != -1 || !slab(r, &t)) return false;
    h->t = t;
    h->prim = 0;
    return true;
  }
  bool occluded(int16_t id, const Ray& r) const {
    float t;
    return id == -1 && slab(r, &t);
  }
};

// Random ids 1..7 in an n^3 box with probability `fill`; with `cells`, 30 % of them are cell ids -1 or -2.
inline VoxelGrid random_grid(uint64_t seed, int n, float fill, bool cells) {
  VoxelGrid g;
  Pcg32 rng(seed);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        if (rng.next_float() >= fill) continue;
        int16_t id = int16_t(1 + int(rng.next_float() * 7));
        if (cells && rng.next_float() < 0.3f) id = rng.next_float() < 0.7f ? -1 : -2;
        g.set(x - n / 3, y, z - n / 2, id);
      }
  return g;
}

// Terrain: a height field of stone under grass, caves, a few floating blocks and slabs on top.
inline VoxelGrid terrain_grid(int n) {
  VoxelGrid g;
  for (int z = 0; z < n; ++z)
    for (int x = 0; x < n; ++x) {
      const int h = int(n / 3 + 6 * std::sin(x * 0.21) * std::cos(z * 0.17) + 3 * std::sin(x * 0.05 + z * 0.07));
      for (int y = 0; y < h; ++y) {
        const bool cave = std::sin(x * 0.3) * std::sin(y * 0.4) * std::sin(z * 0.35) > 0.6;
        if (!cave) g.set(x, y, z, int16_t(y == h - 1 ? 2 : (y < h - 4 ? 1 : 3)));
      }
      if ((x * 7 + z * 13) % 29 == 0) g.set(x, h, z, -1);
    }
  return g;
}

}  // namespace torte::test
