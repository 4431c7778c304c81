#include "voxel/voxel_accel.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "simd/voxel_packet.h"

namespace torte {

namespace {

// Negative ids: the cell's ShapeSet, traced in unit-cell space; `cost` (optional) gets the cell shapes' work.
struct CellHandler {
  const VoxelGridAccel& grid;
  TraversalCost* cost = nullptr;
  bool intersect(int16_t id, const Ray& r, Hit* h) const {
    const VoxelCellGeometry* c = grid.cell(id);
    if (!c || c->set.empty()) return false;
    Hit tmp;
    if (!c->set.intersect_one(r, &tmp, cost)) return false;
    *h = tmp;
    return true;
  }
  bool occluded(int16_t id, const Ray& r) const {
    const VoxelCellGeometry* c = grid.cell(id);
    return c && !c->set.empty() && c->set.occluded_one(r);
  }
};

// A CellHandler that also counts the kd-tree's work (VoxelGridAccel::intersect's cost): a type of its own, so the
// plain traversal has no counters (voxel_traverse.h calls the hooks only where a handler has them).
struct CountingCellHandler : CellHandler {
  void count_node() const { ++cost->nodes; }
  void count_prim() const { ++cost->prims; }
};

// A grid hit as the set's Hit (the encoding at the top of voxel_accel.h).
void encode_hit(const VoxelHit& vh, uint32_t index, Hit* hit) {
  hit->t = vh.t;
  if (vh.face >= 0) {
    hit->prim = voxel_prim(index, false, vh.face, vh.id);
    hit->b1 = vh.u;
    hit->b2 = vh.v;
  } else {
    hit->prim = voxel_prim(index, true, 0, vh.id);
    hit->b1 = vh.cell.b1;
    hit->b2 = vh.cell.b2;
  }
}

Vec3f unit(int axis, float s = 1) {
  Vec3f v(0, 0, 0);
  v[axis] = s;
  return v;
}

}  // namespace

bool VoxelGridAccel::intersect(const Ray& ray, uint32_t index, Hit* hit, TraversalCost* cost) const {
  Ray r = to_set.apply_inverse(ray);
  r.t_max = std::min(ray.t_max, hit->t);
  if (!(r.t_max > 0)) return false;
  VoxelHit vh;
  const bool found = cost ? voxel_intersect(*tree, r, &vh, CountingCellHandler{{*this, cost}})
                          : voxel_intersect(*tree, r, &vh, CellHandler{*this});
  if (!found || !(vh.t < hit->t)) return false;
  encode_hit(vh, index, hit);
  return true;
}

bool VoxelGridAccel::occluded(const Ray& ray) const {
  return voxel_occluded(*tree, to_set.apply_inverse(ray), CellHandler{*this});
}

namespace {
constexpr int kVoxelPacket = 16;

// The grid-space rays and per-ray results of one packet call, kept per thread and grown only: a trace call
// allocates nothing. The packet kernel reads the rays in grid space, so the transformed copy is the one it needs
// (the set-space rays themselves stay in the caller's RaySoA).
struct GridScratch {
  std::vector<Ray> rays;
  std::vector<VoxelHit> hits;
  std::vector<uint8_t> found;
  void reserve(size_t count) {
    if (rays.size() >= count) return;
    rays.resize(count);
    hits.resize(count);
    found.resize(count);
  }
};
GridScratch& grid_scratch() {
  thread_local GridScratch scratch;
  return scratch;
}
}  // namespace

void VoxelGridAccel::intersect_coherent(const RaySoA& set_rays, size_t count, uint32_t index, Hit* hits) const {
  GridScratch& s = grid_scratch();
  s.reserve(count);
  Ray* rays = s.rays.data();
  for (size_t i = 0; i < count; ++i) {
    rays[i] = to_set.apply_inverse(ray_at(set_rays, i));
    rays[i].t_max = std::max(0.0f, std::min(set_rays.t_max[i], hits[i].t));
  }
  const CellHandler cells{*this};
  voxel_intersect_packets(*tree, rays, count, s.hits.data(), s.found.data(), kVoxelPacket, voxel_cell_callbacks(cells));
  for (size_t i = 0; i < count; ++i) {
    // As intersect(): rays with nothing left to search keep their hit.
    if (s.found[i] && rays[i].t_max > 0 && s.hits[i].t < hits[i].t) encode_hit(s.hits[i], index, &hits[i]);
  }
}

void VoxelGridAccel::occluded_coherent(const RaySoA& set_rays, size_t count, uint8_t* blocked) const {
  GridScratch& s = grid_scratch();
  s.reserve(count);
  Ray* rays = s.rays.data();
  for (size_t i = 0; i < count; ++i) {  // rays already blocked: nothing to search
    rays[i] = to_set.apply_inverse(ray_at(set_rays, i));
    if (blocked[i]) rays[i].t_max = 0;
  }
  const CellHandler cells{*this};
  voxel_occluded_packets(*tree, rays, count, s.found.data(), kVoxelPacket, voxel_cell_callbacks(cells));
  for (size_t i = 0; i < count; ++i) blocked[i] = blocked[i] || s.found[i];
}

SurfaceHit VoxelGridAccel::surface(const Hit& hit, const Ray& ray) const {
  const Ray r = to_set.apply_inverse(ray);
  const int16_t id = voxel_prim_id(hit.prim);
  SurfaceHit s;
  s.object = 0;
  if (!voxel_prim_is_cell(hit.prim)) {
    const int face = voxel_prim_face(hit.prim), axis = face / 2;
    const bool positive = face % 2 == 0;
    const int ua = voxel_face_u_axis(axis), va = voxel_face_v_axis(axis);
    const Vec3f p = r.at(hit.t);
    // The face plane is an integer; the uv says where in the face, which picks the voxel even on its edges.
    const float plane = std::round(p[axis]);
    s.p[axis] = plane;
    s.p[ua] = std::round(p[ua] - hit.b1) + hit.b1;
    s.p[va] = std::round(p[va] - hit.b2) + hit.b2;
    s.ng = s.ns = unit(axis, positive ? 1.0f : -1.0f);
    s.uv = Vec2f(hit.b1, hit.b2);
    s.dpdu = unit(ua);
    s.dpdv = unit(va);
    s.material = material_of(id, face);
  } else {
    Ray again = r;
    again.t_max = hit.t * (1 + 1e-5f) + 1e-6f;
    VoxelHit vh;
    const VoxelCellGeometry* c = cell(id);
    if (c && voxel_intersect(*tree, again, &vh, CellHandler{*this}) && vh.face < 0) {
      const SurfaceHit cs = c->set.surface(vh.cell);
      s = cs;
      s.p = cs.p + Vec3f(float(vh.voxel[0]), float(vh.voxel[1]), float(vh.voxel[2]));
      s.material = cs.object < c->object_material.size() ? c->object_material[cs.object] : -1;
    } else {  // not found again (should not happen): a plausible point facing the ray
      s.p = r.at(hit.t);
      s.ng = s.ns = normalize(-r.d);
      const Frame f = Frame::from_z(s.ng);
      s.dpdu = f.s;
      s.dpdv = f.t;
    }
  }
  s.p = to_set.apply_point(s.p);
  s.ng = normalize(to_set.apply_normal(s.ng));
  s.ns = normalize(to_set.apply_normal(s.ns));
  s.dpdu = to_set.apply_vector(s.dpdu);
  s.dpdv = to_set.apply_vector(s.dpdv);
  s.object = 0;
  return s;
}

}  // namespace torte
