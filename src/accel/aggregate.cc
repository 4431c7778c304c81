#include "accel/aggregate.h"

#include <algorithm>
#include <string>
#include <utility>

#include "core/error.h"

namespace torte {

namespace {
// Nodes on the longest root-to-leaf path (1 for a lone leaf): a front-to-back walk holds at most that many
// deferred subtrees.
uint32_t tree_depth(const Bvh2& bvh) {
  const std::vector<Bvh2Node>& nodes = bvh.nodes();
  if (nodes.empty()) return 1;
  uint32_t depth = 1;
  std::vector<std::pair<uint32_t, uint32_t>> todo{{0, 1}};  // node, its depth
  while (!todo.empty()) {
    const auto [node, d] = todo.back();
    todo.pop_back();
    depth = std::max(depth, d);
    if (nodes[node].count == 0) {
      todo.push_back({node + 1, d + 1});
      todo.push_back({nodes[node].offset, d + 1});
    }
  }
  return depth;
}
}  // namespace

void Aggregate::build(std::vector<TriangleMesh>& meshes, const std::vector<Quadric>& quadrics,
                      const std::vector<VoxelGridAccel>& grids, std::vector<std::unique_ptr<Prototype>>& prototypes,
                      const std::vector<Instance>& instances, ProgressCounter* progress,
                      const AccelOptions& options) {
  prototypes_ = &prototypes;
  instances_ = &instances;
  uint64_t triangles = 0;
  for (const TriangleMesh& m : meshes) triangles += m.triangle_count();
  for (const auto& proto : prototypes)
    for (const TriangleMesh& m : proto->meshes) triangles += m.triangle_count();
  layout_ = resolve_layout(options, triangles);
  root_.build(meshes, quadrics, grids, 0, progress, layout_);
  uint32_t object_base = uint32_t(meshes.size() + quadrics.size() + grids.size());
  for (const auto& proto : prototypes) {
    proto->geometry.build(proto->meshes, proto->quadrics, proto->grids, object_base, progress, layout_);
    object_base += uint32_t(proto->meshes.size() + proto->quadrics.size() + proto->grids.size());
  }
  // The instance level: a BVH2 over the instances' world bounds (the bottom levels are the prototypes').
  instance_bounds_.assign(instances.size(), Bounds3f{});
  for (size_t i = 0; i < instances.size(); ++i) {
    if (instances[i].prototype >= prototypes.size()) throw Error("internal: instance of a missing prototype");
    Bounds3f& b = instance_bounds_[i];
    b = instances[i].to_world.apply(prototypes[instances[i].prototype]->geometry.bounds());
    if (!b.empty() && (!in_coordinate_range(b.lo) || !in_coordinate_range(b.hi)))
      throw Error("instance " + std::to_string(i) + " (after unrolling the nesting of groups) places its group beyond "
                  "+-1e18, the range the scene supports");
  }
  instance_bvh_.build(instance_bounds_);
  instance_depth_ = tree_depth(instance_bvh_);
  bounds_ = merge(root_.bounds(), instance_bvh_.bounds());
}

void Aggregate::intersect(const RaySoA& rays, size_t count, Hit* hits, TraceKernel kernel) const {
  root_.intersect(rays, count, hits, kernel);
  if (instances_ && !instances_->empty()) intersect_instances(rays, count, hits);
}

bool Aggregate::intersect_counted(const Ray& ray, Hit* hit, TraversalCost* cost) const {
  *hit = Hit{};
  root_.intersect_one(ray, hit, cost);
  if (instances_ && !instances_->empty()) {
    Ray r = ray;
    r.t_max = std::min(ray.t_max, hit->t);
    instance_bvh_.intersect(r, [&](uint32_t i, Ray& world) {
      const Instance& inst = (*instances_)[i];
      // In instance space with the direction not renormalized, so t means the same in both spaces.
      const Ray local = inst.to_world.apply_inverse(world);
      Hit h;
      if (!(*prototypes_)[inst.prototype]->geometry.intersect_one(local, &h, cost)) return false;
      h.instance = i;
      *hit = h;
      world.t_max = h.t;
      return true;
    }, cost);
  }
  return hit->prim != kNoHit;
}

void Aggregate::occluded(const RaySoA& rays, size_t count, uint8_t* blocked, TraceKernel kernel) const {
  root_.occluded(rays, count, blocked, kernel);
  if (instances_ && !instances_->empty()) occluded_instances(rays, count, blocked);
}

SurfaceHit Aggregate::surface(const Ray& ray, const Hit& hit) const {
  if (hit.instance == kNoHit) return root_.surface(hit, &ray);
  const Instance& inst = (*instances_)[hit.instance];
  const Transform& m = inst.to_world;
  // The ray in instance space, direction not renormalized: t means the same in both spaces.
  const Ray local = m.apply_inverse(ray);
  SurfaceHit s = (*prototypes_)[inst.prototype]->geometry.surface(hit, &local);
  s.p = m.apply_point(s.p);
  // Normals map by the inverse transpose, which keeps them on the front side even under mirroring.
  s.ng = normalize(m.apply_normal(s.ng));
  s.ns = normalize(m.apply_normal(s.ns));
  s.dpdu = m.apply_vector(s.dpdu);
  s.dpdv = m.apply_vector(s.dpdv);
  return s;
}

size_t Aggregate::accel_bytes() const {
  size_t bytes = root_.accel_bytes() + instance_bvh_.nodes().size() * sizeof(Bvh2Node) +
                 instance_bvh_.prim_indices().size() * sizeof(uint32_t);
  if (prototypes_)
    for (const auto& proto : *prototypes_) bytes += proto->geometry.accel_bytes();
  return bytes;
}

}  // namespace torte
