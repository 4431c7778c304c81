// Ray traversal of a voxel grid in its cell space (voxel (x, y, z) = [x, x+1] x [y, y+1] x [z, z+1]).
//
// voxel_intersect / voxel_occluded: front to back through the implicit kd-tree (voxel/voxel_tree.h), with the
// ray's entry and exit distance per node; the split plane of a node is recomputed from its box. Because nodes
// are visited front to back, the first hit is the closest one.
// voxel_intersect_dda / voxel_occluded_dda: the brute-force reference, a 3D-DDA (Amanatides & Woo) over every
// cell of the same root box reading the sparse grid. Both compute every distance as (plane - o) / d, so they
// agree to the bit.
//
// What a ray hits:
// - id > 0, a solid unit cube: the face it enters, at the entry distance. Faces are numbered 2 * axis + s with s
//   = 0 for the face whose outward normal points to +axis and 1 for -axis: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z.
//   A face's (u, v) in [0, 1]^2: x faces (z, y), y faces (x, z), z faces (x, y), the cell-local coordinates.
// - A ray that starts inside a solid voxel (its origin in the voxel or on its boundary, going in) hits the face
//   through which it LEAVES that voxel, from inside (VoxelHit::inside; the face's outward normal then points
//   along the ray). So a camera inside stone sees the inside faces of the voxel it is in, while a ray leaving a
//   face (origin offset outwards, as the renderer does) never hits its own voxel. No hit when the ray ends
//   before leaving the voxel.
// - id < 0, a cell shape: the cell handler is called with the ray in the cell's unit space (origin minus the
//   voxel's corner, same direction, so the same t) and t_max clipped to where the ray leaves the cell (plus
//   1e-5 relative slack, so faces on the cell's boundary are found from inside); geometry
//   must lie in [0, 1]^3. Handlers: `bool intersect(int16_t id, const Ray&, Hit*) const` (closest, fills Hit with
//   t) and `bool occluded(int16_t id, const Ray&) const`. A handler may also count the work (the traversal_cost
//   AOV): `void count_node() const` for each kd-tree node descended, `void count_prim() const` for each solid
//   voxel or cell tested; handlers without them cost nothing.
// - id 0: nothing.
#pragma once
#include <algorithm>
#include <cmath>

#include "accel/hit.h"
#include "core/ray.h"
#include "voxel/voxel_tree.h"

namespace torte {

struct VoxelHit {
  float t = kInfinity;
  int voxel[3] = {0, 0, 0};  // grid coordinates of the voxel hit
  int16_t id = 0;
  int8_t face = -1;     // cubes: 0..5 as above; -1 for a cell shape
  bool inside = false;  // the ray started inside this solid voxel (face = exit face)
  float u = 0, v = 0;   // cube face uv
  Hit cell;             // cell shapes: the handler's hit (unit-cell space)
};

// Cell handler that sees no geometry in negative-id cells.
struct NoVoxelCells {
  bool intersect(int16_t, const Ray&, Hit*) const { return false; }
  bool occluded(int16_t, const Ray&) const { return false; }
};

inline int voxel_face_u_axis(int axis) { return axis == 0 ? 2 : 0; }
inline int voxel_face_v_axis(int axis) { return axis == 1 ? 2 : 1; }

namespace voxel_detail {

enum Step { kContinue, kHit, kStop };

template <class Cells>
inline void count_node(const Cells& cells) {
  if constexpr (requires { cells.count_node(); }) cells.count_node();
}
template <class Cells>
inline void count_prim(const Cells& cells) {
  if constexpr (requires { cells.count_prim(); }) cells.count_prim();
}

// The ray relative to the tree's origin.
struct LocalRay {
  Vec3f o, d, inv;
  float t_max;
  int origin[3];
};

inline bool make_local(const VoxelTree& tree, const Ray& ray, LocalRay* r, float* t0, float* t1, int* entry) {
  const int* org = tree.origin();
  const int* lg = tree.log2_size();
  *t0 = 0;
  *t1 = ray.t_max;
  *entry = -1;
  for (int a = 0; a < 3; ++a) {
    r->origin[a] = org[a];
    r->o[a] = ray.o[a] - float(org[a]);
    r->d[a] = ray.d[a];
    r->inv[a] = 1.0f / ray.d[a];
    const float size = float(1 << lg[a]);
    if (ray.d[a] == 0) {
      if (r->o[a] < 0 || r->o[a] > size) return false;
      continue;
    }
    float tn = (0.0f - r->o[a]) * r->inv[a], tf = (size - r->o[a]) * r->inv[a];
    if (tn > tf) std::swap(tn, tf);
    if (tn > *t0) {
      *t0 = tn;
      *entry = a;
    }
    *t1 = std::min(*t1, tf);
  }
  r->t_max = ray.t_max;
  return *t0 <= *t1;
}

// floor(p) as an int, limited to [lo - 1, hi]: a position far outside the box (or NaN, from a NaN ray) must not
// reach the float-to-int conversion, which is undefined out of range. The caller's clamp gives the same cell.
inline int floor_within(float p, int lo, int hi) {
  const float f = std::floor(p);
  if (!(f >= float(lo - 1))) return lo - 1;
  return f <= float(hi) ? int(f) : hi;
}

// The cell of box [blo, bhi) where the ray is at distance t, having entered through a plane of axis `entry`
// (-1: the origin's own cell).
inline void entry_cell(const LocalRay& r, const int blo[3], const int bhi[3], float t, int entry, int v[3]) {
  for (int a = 0; a < 3; ++a) {
    if (a == entry) {
      v[a] = r.d[a] > 0 ? blo[a] : bhi[a] - 1;
    } else {
      const float p = entry < 0 ? r.o[a] : r.o[a] + r.d[a] * t;
      int c = floor_within(p, blo[a], bhi[a]);
      // On a cell boundary, the cell the ray goes into (as the tree picks the side of a split plane).
      if (float(c) == p && r.d[a] < 0) --c;
      v[a] = std::clamp(c, blo[a], bhi[a] - 1);
    }
  }
}

// Visits the cells of box [blo, bhi) along the ray over [t0, t1], front to back; visit(v, t_enter, t_exit,
// entry_axis) returns a Step.
template <class Visit>
Step walk_cells(const LocalRay& r, const int blo[3], const int bhi[3], float t0, float t1, int entry, Visit&& visit) {
  int v[3], step[3];
  float tnext[3];
  entry_cell(r, blo, bhi, t0, entry, v);
  for (int a = 0; a < 3; ++a) {
    step[a] = r.d[a] > 0 ? 1 : -1;
    tnext[a] = r.d[a] == 0 ? kInfinity : (float(v[a] + (r.d[a] > 0)) - r.o[a]) * r.inv[a];
  }
  float tc = t0;
  int axis = entry;
  for (;;) {
    const int na = tnext[0] <= tnext[1] ? (tnext[0] <= tnext[2] ? 0 : 2) : (tnext[1] <= tnext[2] ? 1 : 2);
    const float te = tnext[na];
    const Step s = visit(v, tc, std::min(te, t1), axis);
    if (s != kContinue) return s;
    if (te >= t1) return kContinue;
    v[na] += step[na];
    if (v[na] < blo[na] || v[na] >= bhi[na]) return kContinue;
    tc = te;
    axis = na;
    tnext[na] = (float(v[na] + (r.d[na] > 0)) - r.o[na]) * r.inv[na];
  }
}

inline void face_uv(const LocalRay& r, const int v[3], float t, int axis, VoxelHit* h) {
  const int ua = voxel_face_u_axis(axis), va = voxel_face_v_axis(axis);
  h->u = std::clamp(r.o[ua] + r.d[ua] * t - float(v[ua]), 0.0f, 1.0f);
  h->v = std::clamp(r.o[va] + r.d[va] * t - float(v[va]), 0.0f, 1.0f);
}

// A solid voxel v entered at t through axis `entry` (-1: the ray starts inside it).
inline Step solid_voxel(const LocalRay& r, const int v[3], int16_t id, float t, int entry, VoxelHit* h) {
  bool inside = false;
  int axis = entry;
  if (entry < 0) {  // leave through the nearest exit plane
    inside = true;
    t = kInfinity;
    for (int a = 0; a < 3; ++a) {
      if (r.d[a] == 0) continue;
      const float te = (float(v[a] + (r.d[a] > 0)) - r.o[a]) * r.inv[a];
      if (te < t) {
        t = te;
        axis = a;
      }
    }
    if (!(t <= r.t_max) || axis < 0) return kStop;
  }
  h->t = t;
  for (int a = 0; a < 3; ++a) h->voxel[a] = v[a] + r.origin[a];
  h->id = id;
  h->inside = inside;
  // Entering along +axis hits the -axis face (odd); leaving along +axis the +axis face (even).
  h->face = int8_t(2 * axis + ((r.d[axis] > 0) != inside ? 1 : 0));
  face_uv(r, v, t, axis, h);
  return kHit;
}

template <bool kAny, class Cells>
Step cell_voxel(const LocalRay& r, const int v[3], int16_t id, float t_exit, const Cells& cells, VoxelHit* h) {
  // t_max a little past the cell's exit: geometry on the exit face of the cell (a slab's side seen from inside)
  // must not be lost to rounding.
  const float t_end = t_exit + 1e-5f * std::max(1.0f, t_exit);
  const Ray local{{r.o.x - float(v[0]), r.o.y - float(v[1]), r.o.z - float(v[2])}, r.d, std::min(t_end, r.t_max)};
  if constexpr (kAny) {
    if (!cells.occluded(id, local)) return kContinue;
    h->t = 0;
  } else {
    Hit ch;
    if (!cells.intersect(id, local, &ch)) return kContinue;
    h->t = ch.t;
    h->cell = ch;
  }
  for (int a = 0; a < 3; ++a) h->voxel[a] = v[a] + r.origin[a];
  h->id = id;
  h->face = -1;
  h->inside = false;
  return kHit;
}

template <bool kAny, class Cells>
bool trace_tree(const VoxelTree& tree, const Ray& ray, const Cells& cells, VoxelHit* out) {
  LocalRay r;
  float t0, t1;
  int entry;
  if (!make_local(tree, ray, &r, &t0, &t1, &entry)) return false;
  // The current node's box lives in small arrays indexed by axis; stack entries are written and read field by
  // field with equal sizes (a byte store followed by a wide load of the same entry stalls store forwarding).
  struct Entry {
    VoxelNode node;
    int32_t entry;
    int32_t lo[3];
    int32_t lg[3];
    float tn, tf;
  };
  Entry stack[100];
  int sp = 0;
  const int* lg0 = tree.log2_size();
  struct {
    VoxelNode node;
    int32_t entry;
    int32_t lo[3];
    int32_t lg[3];
    float tn, tf;
  } cur{tree.root(), entry, {0, 0, 0}, {lg0[0], lg0[1], lg0[2]}, t0, t1};
  const VoxelNode* nodes = tree.nodes().data();
  for (;;) {
    while (!cur.node.is_leaf()) {
      count_node(cells);
      const int a = cur.node.axis();
      const VoxelNode* kids = nodes + 2 * size_t(cur.node.pair());
      const int lga = --cur.lg[a];
      const int split = cur.lo[a] + (1 << lga);
      const float oa = r.o[a], fsplit = float(split);
      const bool below = oa < fsplit || (oa == fsplit && r.d[a] < 0);
      const VoxelNode near = kids[below ? 0 : 1], far = kids[below ? 1 : 0];
      const int near_lo = below ? cur.lo[a] : split, far_lo = below ? split : cur.lo[a];
      const float ts = r.d[a] == 0 ? -1.0f : (fsplit - oa) * r.inv[a];
      if (ts > cur.tf || ts <= 0) {  // the near side only
        cur.node = near;
        cur.lo[a] = near_lo;
        continue;
      }
      if (ts < cur.tn) {  // the far side only
        cur.node = far;
        cur.lo[a] = far_lo;
        continue;
      }
      if (!far.is_leaf() || far.id() != 0) {
        Entry& e = stack[sp++];
        e.node = far;
        e.entry = a;
        for (int k = 0; k < 3; ++k) {
          e.lo[k] = cur.lo[k];
          e.lg[k] = cur.lg[k];
        }
        e.lo[a] = far_lo;
        e.tn = ts;
        e.tf = cur.tf;
      }
      cur.node = near;
      cur.lo[a] = near_lo;
      cur.tf = ts;
    }
    const int16_t id = cur.node.id();
    if (id != 0) {
      const int blo[3] = {cur.lo[0], cur.lo[1], cur.lo[2]};
      const int bhi[3] = {blo[0] + (1 << cur.lg[0]), blo[1] + (1 << cur.lg[1]), blo[2] + (1 << cur.lg[2])};
      Step s;
      if (id > 0) {
        count_prim(cells);
        int v[3];
        entry_cell(r, blo, bhi, cur.tn, cur.entry, v);
        s = solid_voxel(r, v, id, cur.tn, cur.entry, out);
      } else {
        s = walk_cells(r, blo, bhi, cur.tn, cur.tf, cur.entry, [&](const int* v, float, float te, int) {
          count_prim(cells);
          return cell_voxel<kAny>(r, v, id, te, cells, out);
        });
      }
      if (s == kHit) return true;
      if (s == kStop) return false;
    }
    if (sp == 0) return false;
    const Entry& e = stack[--sp];
    cur.node = e.node;
    cur.entry = e.entry;
    for (int k = 0; k < 3; ++k) {
      cur.lo[k] = e.lo[k];
      cur.lg[k] = e.lg[k];
    }
    cur.tn = e.tn;
    cur.tf = e.tf;
  }
}

template <bool kAny, class Cells>
bool trace_dda(const VoxelTree& tree, const VoxelGrid& grid, const Ray& ray, const Cells& cells, VoxelHit* out) {
  LocalRay r;
  float t0, t1;
  int entry;
  if (!make_local(tree, ray, &r, &t0, &t1, &entry)) return false;
  const int* lg = tree.log2_size();
  const int blo[3] = {0, 0, 0}, bhi[3] = {1 << lg[0], 1 << lg[1], 1 << lg[2]};
  const Step s = walk_cells(r, blo, bhi, t0, t1, entry, [&](const int* v, float tc, float te, int axis) {
    const int16_t id = grid.get(v[0] + r.origin[0], v[1] + r.origin[1], v[2] + r.origin[2]);
    if (id > 0) return solid_voxel(r, v, id, tc, axis, out);
    if (id < 0) return cell_voxel<kAny>(r, v, id, te, cells, out);
    return kContinue;
  });
  return s == kHit;
}

}  // namespace voxel_detail

// Closest hit of a ray (cell space) with t in [0, ray.t_max].
template <class Cells = NoVoxelCells>
bool voxel_intersect(const VoxelTree& tree, const Ray& ray, VoxelHit* hit, const Cells& cells = {}) {
  return voxel_detail::trace_tree<false>(tree, ray, cells, hit);
}
template <class Cells = NoVoxelCells>
bool voxel_occluded(const VoxelTree& tree, const Ray& ray, const Cells& cells = {}) {
  VoxelHit h;
  return voxel_detail::trace_tree<true>(tree, ray, cells, &h);
}
// The reference: the tree only supplies the root box.
template <class Cells = NoVoxelCells>
bool voxel_intersect_dda(const VoxelTree& tree, const VoxelGrid& grid, const Ray& ray, VoxelHit* hit,
                         const Cells& cells = {}) {
  return voxel_detail::trace_dda<false>(tree, grid, ray, cells, hit);
}
template <class Cells = NoVoxelCells>
bool voxel_occluded_dda(const VoxelTree& tree, const VoxelGrid& grid, const Ray& ray, const Cells& cells = {}) {
  VoxelHit h;
  return voxel_detail::trace_dda<true>(tree, grid, ray, cells, &h);
}

}  // namespace torte
