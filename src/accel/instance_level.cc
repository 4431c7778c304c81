// The instance level of Aggregate, traced in batches (see accel/aggregate.h). Every ray walks the instance BVH2
// front to back, as a scalar traversal would, but stops at each leaf it reaches: the leaf's instances become work
// items, the items of all rays are binned by prototype and each bin goes through the SIMD kernels as one RaySoA
// (every ray in its own instance's space), then the rays resume with t_max clipped to what the bin found.
// Binning by prototype rather than instance keeps bins large when thousands of instances share a few groups.
#include <algorithm>
#include <vector>

#include "accel/aggregate.h"

namespace torte {

namespace {

// One suspended subtree of a ray's top-level walk.
struct StackEntry {
  uint32_t node;
  float t_near;
};
static_assert(sizeof(StackEntry) == 8);

// An instance a ray must be traced through.
struct WorkItem {
  uint32_t ray, instance;
};
static_assert(sizeof(WorkItem) == 8);

// Per-thread working memory of one batch, grown only: tracing a queue allocates nothing once warm.
struct InstanceScratch {
  std::vector<SlabRay> slabs;             // per ray, for the box tests of its walk
  std::vector<StackEntry> stacks;         // per ray, `depth` entries
  std::vector<uint32_t> sp;               // per ray: entries on its stack
  std::vector<uint32_t> active, later;    // rays whose walk goes on in this round / the next
  std::vector<WorkItem> work, binned;     // one round's items, in ray order / grouped by prototype
  std::vector<uint32_t> bin_start;        // per prototype + 1
  std::vector<float> rays;                // 7 arrays of one bin's rays in instance space (RaySoA)
  std::vector<Hit> hits;
  std::vector<uint8_t> blocked;
};

InstanceScratch& instance_scratch() {
  thread_local InstanceScratch s;
  return s;
}

template <class T>
T* at_least(std::vector<T>& v, size_t n) {
  if (v.size() < n) v.resize(n, T{});
  return v.data();
}

// The walks of one batch. limit(i) is ray i's current t_max (its hit so far; 0 once it needs nothing more).
class TopLevelWalk {
 public:
  TopLevelWalk(const Bvh2& bvh, const std::vector<Bounds3f>& boxes, uint32_t depth, InstanceScratch& s)
      : nodes_(bvh.nodes()), prims_(bvh.prim_indices()), boxes_(boxes), depth_(depth), s_(s) {}

  // Starts the walk of every ray whose t_max is positive and which enters the root box.
  template <class Limit>
  void start(const RaySoA& rays, size_t count, Limit&& limit) {
    s_.active.clear();
    if (nodes_.empty()) return;
    // SlabRay has no default constructor: the scratch holds raw storage for it.
    if (s_.slabs.size() < count) s_.slabs.assign(count, SlabRay(Ray{}));
    at_least(s_.stacks, count * size_t(depth_));
    at_least(s_.sp, count);
    for (size_t i = 0; i < count; ++i) {
      s_.sp[i] = 0;
      const float t_max = limit(uint32_t(i));
      if (!(t_max > 0)) continue;
      s_.slabs[i] = SlabRay(ray_at(rays, i, t_max));
      float t_near;
      if (!s_.slabs[i].hits(nodes_[0].bounds, t_max, &t_near)) continue;
      s_.stacks[i * depth_] = {0, t_near};
      s_.sp[i] = 1;
      s_.active.push_back(uint32_t(i));
    }
  }

  // One round: every active ray walks on to its next leaf holding an instance whose box it enters before
  // limit(ray), whose instances become work items (in ray order); rays with subtrees left stay active.
  template <class Limit>
  void round(Limit&& limit) {
    s_.work.clear();
    s_.later.clear();
    for (const uint32_t i : s_.active) {
      const float t_max = limit(i);
      if (t_max > 0 && advance(i, t_max) && s_.sp[i] > 0) s_.later.push_back(i);
    }
    std::swap(s_.active, s_.later);
  }

  bool done() const { return s_.active.empty(); }

 private:
  // Walks ray i to its next non-empty leaf; false when the walk ended without one.
  bool advance(uint32_t i, float t_max) {
    StackEntry* stack = s_.stacks.data() + size_t(i) * depth_;
    uint32_t& sp = s_.sp[i];
    const SlabRay& slab = s_.slabs[i];
    while (sp > 0) {
      const StackEntry e = stack[--sp];
      if (!(e.t_near <= t_max)) continue;  // nothing in it can be closer than the hit so far
      uint32_t node = e.node;
      for (;;) {
        const Bvh2Node& n = nodes_[node];
        if (n.count > 0) {
          const size_t before = s_.work.size();
          for (uint32_t j = 0; j < n.count; ++j) {
            const uint32_t k = prims_[n.offset + j];
            if (slab.hits(boxes_[k], t_max)) s_.work.push_back({i, k});
          }
          if (s_.work.size() > before) return true;
          break;
        }
        const uint32_t left = node + 1, right = n.offset;
        float t_left, t_right;
        const bool hit_left = slab.hits(nodes_[left].bounds, t_max, &t_left);
        const bool hit_right = slab.hits(nodes_[right].bounds, t_max, &t_right);
        if (hit_left && hit_right) {  // the nearer next, the farther for later (as Bvh2::intersect)
          const bool left_first = t_left <= t_right;
          stack[sp++] = left_first ? StackEntry{right, t_right} : StackEntry{left, t_left};
          node = left_first ? left : right;
        } else if (hit_left || hit_right) {
          node = hit_left ? left : right;
        } else {
          break;
        }
      }
    }
    return false;
  }

  const std::vector<Bvh2Node>& nodes_;
  const std::vector<uint32_t>& prims_;
  const std::vector<Bounds3f>& boxes_;
  uint32_t depth_;
  InstanceScratch& s_;
};

// Groups s.work by prototype into s.binned (stable: rays stay in queue order within a bin, which keeps coherent
// queues coherent) and calls trace(prototype, first, n, local) per bin [first, first + n) of s.binned with its
// rays written, in instance space with t_max = limit(ray), to the RaySoA `local`.
template <class Limit, class Trace>
void trace_bins(const std::vector<Instance>& instances, size_t prototypes, const RaySoA& world, Limit&& limit,
                InstanceScratch& s, Trace&& trace) {
  const size_t n_work = s.work.size();
  if (n_work == 0) return;
  uint32_t* start = at_least(s.bin_start, prototypes + 1);
  std::fill(start, start + prototypes + 1, 0u);
  for (const WorkItem& w : s.work) ++start[instances[w.instance].prototype + 1];
  for (size_t p = 0; p < prototypes; ++p) start[p + 1] += start[p];
  WorkItem* binned = at_least(s.binned, n_work);
  for (const WorkItem& w : s.work) binned[start[instances[w.instance].prototype]++] = w;
  // start[p] is now the end of bin p.
  float* f = at_least(s.rays, 7 * n_work);
  for (size_t p = 0, first = 0; p < prototypes; first = start[p], ++p) {
    const size_t n = start[p] - first;
    if (n == 0) continue;
    const RaySoA local{f, f + n, f + 2 * n, f + 3 * n, f + 4 * n, f + 5 * n, f + 6 * n};
    for (size_t j = 0; j < n; ++j) {
      const WorkItem& w = binned[first + j];
      // Direction mapped but not renormalized: t means the same distance in both spaces, so hits compare.
      const Ray r = instances[w.instance].to_world.apply_inverse(ray_at(world, w.ray, limit(w.ray)));
      f[j] = r.o.x, f[n + j] = r.o.y, f[2 * n + j] = r.o.z;
      f[3 * n + j] = r.d.x, f[4 * n + j] = r.d.y, f[5 * n + j] = r.d.z, f[6 * n + j] = r.t_max;
    }
    trace(uint32_t(p), first, n, local);
  }
}

// Both queries' batch loop: every ray walks the instance BVH2 round by round (TopLevelWalk), and each round's work
// items are traced bin by bin (trace_bins) through `trace`, which folds a bin's results into the rays' own so that
// limit(ray) sees them in the next round. A template, so the per-bin body is resolved at compile time.
template <class Limit, class Trace>
void walk_and_trace(const Bvh2& bvh, const std::vector<Bounds3f>& boxes, uint32_t depth,
                    const std::vector<Instance>& instances, size_t prototypes, const RaySoA& rays, size_t count,
                    InstanceScratch& s, Limit&& limit, Trace&& trace) {
  TopLevelWalk walk(bvh, boxes, depth, s);
  walk.start(rays, count, limit);
  while (!walk.done()) {
    walk.round(limit);
    trace_bins(instances, prototypes, rays, limit, s, trace);
  }
}

}  // namespace

void Aggregate::intersect_instances(const RaySoA& rays, size_t count, Hit* hits) const {
  InstanceScratch& s = instance_scratch();
  walk_and_trace(instance_bvh_, instance_bounds_, instance_depth_, *instances_, prototypes_->size(), rays, count, s,
                 [&](uint32_t i) { return std::min(rays.t_max[i], hits[i].t); },
                 [&](uint32_t p, size_t first, size_t n, const RaySoA& local) {
                   // Single-ray kernels (16 rays set up at a time): a bin mixes instance spaces, so neighbours in
                   // it are not coherent enough for packets (measured slower on scenes/instancing.lua).
                   Hit* found = at_least(s.hits, n);
                   (*prototypes_)[p]->geometry.intersect(local, n, found, TraceKernel::kSingle);
                   for (size_t j = 0; j < n; ++j) {
                     const WorkItem& w = s.binned[first + j];
                     Hit& h = hits[w.ray];
                     if (found[j].prim == kNoHit || !(found[j].t < h.t)) continue;
                     h = found[j];
                     h.instance = w.instance;
                   }
                 });
}

void Aggregate::occluded_instances(const RaySoA& rays, size_t count, uint8_t* blocked) const {
  InstanceScratch& s = instance_scratch();
  walk_and_trace(instance_bvh_, instance_bounds_, instance_depth_, *instances_, prototypes_->size(), rays, count, s,
                 [&](uint32_t i) { return blocked[i] ? 0.0f : rays.t_max[i]; },
                 [&](uint32_t p, size_t first, size_t n, const RaySoA& local) {
                   uint8_t* b = at_least(s.blocked, n);
                   (*prototypes_)[p]->geometry.occluded(local, n, b, TraceKernel::kSingle);
                   for (size_t j = 0; j < n; ++j) blocked[s.binned[first + j].ray] |= b[j];
                 });
}

}  // namespace torte
