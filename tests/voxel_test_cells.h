// A unit-cell handler shared by the voxel tests and the voxel benchmark: id -1 is a bottom slab, other negative
// ids are empty (the traversal's cell callback interface, voxel/voxel_traverse.h).
#pragma once
#include <algorithm>
#include <utility>

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

}  // namespace torte::test
