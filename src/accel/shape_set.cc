#include "accel/shape_set.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/parallel.h"
#include "simd/traverse.h"

namespace torte {

void ShapeSet::build(std::vector<TriangleMesh>& meshes, const std::vector<Quadric>& quadrics,
                     ProgressCounter* progress, BvhLayout layout) {
  if (layout == BvhLayout::kAuto) throw Error("internal: ShapeSet::build takes a resolved layout");
  layout_ = layout;
  tri_leaves_ = {}, ctri_bvh_ = {}, ptri_leaves_ = {};  // a rebuild in the other layout keeps none of these
  meshes_ = &meshes;
  quadrics_ = &quadrics;
  // The set's input numbering: mesh after mesh.
  std::vector<uint32_t> mesh_first;
  size_t input_triangles = 0;
  for (const TriangleMesh& mesh : meshes) {
    mesh_first.push_back(uint32_t(input_triangles));
    input_triangles += mesh.triangle_count();
  }
  if (input_triangles > (size_t(1) << 31)) throw Error("more than 2^31 triangles in one scene or group");
  // Triangles: the wide BVH over bounds computed chunk by chunk straight into the builder's references (an
  // array of them would cost 24 B/tri at the build's peak), its leaf-order vertex copy (read from the meshes),
  // then the owned meshes rewritten in leaf order.
  const auto report = [&](size_t units) {
    if (progress) progress->add(units);
  };
  BvhBuildOptions options;
  options.progress = progress;
  // Small sets price leaves per triangle (block 1), so the SAH splits down to tight leaves: there the node memory
  // and build time that block 8 saves are nothing, and a ray that skips a leaf's box skips its test (the Cornell
  // box's 32 triangles: 17 leaves in 4 nodes instead of 4 leaves of 8 in one; 12 % fewer render instructions).
  if (input_triangles <= kFineLeavesMaxTriangles) options.leaf_block_size = 1;
  const auto bounds_of = [&](size_t begin, size_t end, Bounds3f* out) {
    // A chunk may span meshes (small ones): walk them from the one holding `begin`.
    uint32_t m = meshes.empty() ? 0 : mesh_holding(mesh_first, uint32_t(begin));
    for (size_t g = begin; g < end; ++g) {
      while (m + 1 < meshes.size() && g >= mesh_first[m + 1]) ++m;
      out[g - begin] = meshes[m].triangle_bounds(g - mesh_first[m]);
    }
    report(end - begin);
  };
  tri_bvh_ = build_wide_bvh<kDefaultBvhWidth>(input_triangles, bounds_of, options);
  report(input_triangles - tri_bvh_.prim_indices.size());  // triangles the tree left out (empty bounds)
  const std::span<const TriangleMesh> mesh_span(meshes);
  // Every layout's leaves come from the tree's order before store_in_leaf_order consumes it; packed leaves
  // rewrite the tree's leaf references (to their blocks), before the compact layout quantises the nodes.
  if (layout == BvhLayout::kDefault) {
    tri_leaves_ = make_triangle_leaves(tri_bvh_, mesh_span, mesh_first);
  } else {
    ptri_leaves_ = make_packed_leaves(tri_bvh_, mesh_span, mesh_first);
  }
  report(input_triangles / 2);
  store_in_leaf_order(meshes, mesh_first);
  if (layout == BvhLayout::kCompact) {
    ctri_bvh_ = quantize(std::move(tri_bvh_));
    tri_bvh_ = {};
  }
  report(input_triangles - input_triangles / 2);
  std::vector<Bounds3f> quadric_bounds(quadrics.size());
  for (size_t q = 0; q < quadrics.size(); ++q) quadric_bounds[q] = world_bounds(quadrics[q]);
  quadric_bvh_.build(quadric_bounds);
  bounds_ = merge(layout == BvhLayout::kCompact ? ctri_bvh_.bounds : tri_bvh_.bounds, quadric_bvh_.bounds());
}

// Rewrites every owned mesh's index triples in the order its triangles take in the leaves, then the set numbers
// its triangles by leaf position: a hit needs no map back, and a set of one owned mesh needs no per-triangle
// table at all (its triangle i is the mesh's triangle i). Triangles the tree left out (empty bounds: never hit)
// go last in their mesh. Placed meshes (TriangleMesh::make_placed) share their triples with the script and keep
// their order; a set with one of them, or with several meshes, keeps a table of each triangle's place in the
// meshes concatenated (4 B/tri). The tree's prim_indices are dropped: the meshes or that table carry the order.
//
// Parallel over blocks of leaf positions: a triangle's index in its mesh is its rank among the mesh's triangles
// in leaf order, so each block counts its triangles per mesh, an exclusive scan over the blocks gives every
// block its starting rank per mesh, and a second pass writes. The reordered triples are staged and copied back
// over each mesh's own index array.
void ShapeSet::store_in_leaf_order(std::vector<TriangleMesh>& meshes, const std::vector<uint32_t>& mesh_first) {
  auto& order = tri_bvh_.prim_indices;  // leaf position -> input triangle
  const size_t n = order.size(), mesh_count = meshes.size();
  const size_t input_triangles = mesh_first.empty() ? 0 : mesh_first.back() + meshes.back().triangle_count();
  triangle_count_ = uint32_t(n);
  const bool one_mesh = mesh_count == 1;
  bool any_placed = false, any_owned = false;
  for (const TriangleMesh& m : meshes) (m.placed() ? any_placed : any_owned) |= m.triangle_count() > 0;
  free_storage(tri_ref_);
  mesh_first_.clear();
  const bool table = (!one_mesh || any_placed) && n > 0;
  if (table) mesh_first_ = mesh_first;
  if (!any_owned) {  // the tree's order is the table: input triangle = mesh_first[m] + its index in mesh m
    if (table) tri_ref_ = std::move(order);
    free_storage(order);
    pack_triangle_refs(meshes);
    return;
  }
  if (table) tri_ref_ = make_huge_page_vector<uint32_t>(n);
  HugePageVector<uint32_t> scratch = make_huge_page_vector<uint32_t>(3 * input_triangles);
  const auto mesh_of = [&](uint32_t g) { return one_mesh ? 0u : mesh_holding(mesh_first, g); };
  // Blocks of at least 64 k triangles, and at most 4 M per-(block, mesh) counters.
  const size_t blocks =
      std::max<size_t>(1, std::min({n / 65536, size_t(64), (size_t(4) << 20) / std::max<size_t>(mesh_count, 1)}));
  const auto block_begin = [&](size_t b) { return b * n / blocks; };
  std::vector<uint32_t> rank(blocks * mesh_count, 0);  // block b, mesh m at b * mesh_count + m
  if (!one_mesh)
    parallel_for(size_t(0), blocks, [&](size_t b) {
      for (size_t i = block_begin(b); i < block_begin(b + 1); ++i) ++rank[b * mesh_count + mesh_of(order[i])];
    });
  else
    for (size_t b = 0; b < blocks; ++b) rank[b] = uint32_t(block_begin(b + 1) - block_begin(b));
  std::vector<uint32_t> placed(mesh_count, 0);  // triangles of each mesh in the tree
  for (size_t m = 0; m < mesh_count; ++m)
    for (size_t b = 0; b < blocks; ++b) {
      const uint32_t c = rank[b * mesh_count + m];
      rank[b * mesh_count + m] = placed[m];
      placed[m] += c;
    }
  // Owned mesh m's new triples go to scratch triangles [mesh_first[m], mesh_first[m] + its count).
  const auto stage = [&](uint32_t m, size_t local, const uint32_t* t) {
    std::memcpy(scratch.data() + 3 * (mesh_first[m] + local), t, 12);
  };
  parallel_for(size_t(0), blocks, [&](size_t b) {
    uint32_t* next = rank.data() + b * mesh_count;  // no element when there are no meshes
    for (size_t i = block_begin(b); i < block_begin(b + 1); ++i) {
      const uint32_t g = order[i], m = mesh_of(g);
      if (meshes[m].placed()) {
        tri_ref_[i] = g;  // keeps its order
        continue;
      }
      const uint32_t local = next[m]++;
      if (table) tri_ref_[i] = mesh_first[m] + local;
      stage(m, local, meshes[m].triangle(g - mesh_first[m]));
    }
  });
  if (n < input_triangles) {
    std::vector<bool> in_tree(input_triangles, false);
    for (uint32_t g : order) in_tree[g] = true;
    for (uint32_t m = 0; m < mesh_count; ++m) {
      if (meshes[m].placed()) continue;
      for (size_t t = 0, next = placed[m]; t < meshes[m].triangle_count(); ++t)
        if (!in_tree[mesh_first[m] + t]) stage(m, next++, meshes[m].triangle(t));
    }
  }
  parallel_for(uint32_t(0), uint32_t(mesh_count), [&](uint32_t m) {
    if (!meshes[m].placed() && !meshes[m].indices.empty())
      std::memcpy(meshes[m].indices.data(), scratch.data() + 3 * size_t(mesh_first[m]), 4 * meshes[m].indices.size());
  });
  free_storage(order);
  pack_triangle_refs(meshes);
}

void ShapeSet::pack_triangle_refs(const std::vector<TriangleMesh>& meshes) {
  ref_local_bits_ = 0;
  if (tri_ref_.empty()) return;
  size_t largest = 0;
  for (const TriangleMesh& m : meshes) largest = std::max(largest, m.triangle_count());
  const int local_bits = std::bit_width(largest), mesh_bits = std::bit_width(meshes.size() - 1);
  if (local_bits + mesh_bits > 32 || local_bits >= 32) return;  // stays a concatenated index, found by search
  parallel_for(size_t(0), tri_ref_.size(), [&](size_t i) {
    const uint32_t g = tri_ref_[i], m = mesh_holding(mesh_first_, g);
    tri_ref_[i] = m << local_bits | (g - mesh_first_[m]);
  });
  ref_local_bits_ = uint8_t(local_bits);
}

bool ShapeSet::intersect_one(const Ray& ray, Hit* hit, TraversalCost* cost) const {
  Ray r = ray;
  r.t_max = std::min(ray.t_max, hit->t);
  if (!(r.t_max > 0) || empty()) return false;
  const SingleRay one(r);
  Hit h;
  intersect(one.soa(), 1, &h, TraceKernel::kSingle, cost);
  if (h.prim == kNoHit || !(h.t < hit->t)) return false;
  h.instance = hit->instance;
  *hit = h;
  return true;
}

bool ShapeSet::occluded_one(const Ray& ray) const {
  if (empty()) return false;
  const SingleRay one(ray);
  uint8_t blocked = 0;
  occluded(one.soa(), 1, &blocked, TraceKernel::kSingle);
  return blocked != 0;
}

void ShapeSet::intersect(const RaySoA& rays, size_t count, Hit* hits, TraceKernel kernel,
                         TraversalCost* costs) const {
  if (triangle_count() > 0) {
    with_layout([&](const auto& bvh, const auto& leaves) {
      if (costs) {
        intersect_closest_counted(bvh, leaves, rays, count, hits, costs);
      } else if (kernel != TraceKernel::kSingle) {
        intersect_closest_packets(bvh, leaves, rays, count, hits, int(kernel));
      } else {
        intersect_closest(bvh, leaves, rays, count, hits);
      }
    });
  } else {
    std::fill(hits, hits + count, Hit{});
  }
  if (quadric_count() > 0) intersect_quadrics(rays, count, hits, costs);
}

void ShapeSet::intersect_quadrics(const RaySoA& rays, size_t count, Hit* hits, TraversalCost* costs) const {
  const uint32_t ntri = triangle_count();
  for (size_t i = 0; i < count; ++i) {
    Ray r = ray_at(rays, i, std::min(rays.t_max[i], hits[i].t));
    if (!(r.t_max > 0)) continue;
    quadric_bvh_.intersect(r, [&](uint32_t q, Ray& ray) {
      float t;
      Vec2f uv;
      if (!torte::intersect((*quadrics_)[q], ray, &t, &uv)) return false;
      ray.t_max = t;
      hits[i] = {t, ntri + q, uv.x, uv.y};
      return true;
    }, costs ? &costs[i] : nullptr);
  }
}

void ShapeSet::occluded(const RaySoA& rays, size_t count, uint8_t* blocked, TraceKernel kernel) const {
  if (triangle_count() > 0) {
    with_layout([&](const auto& bvh, const auto& leaves) {
      if (kernel != TraceKernel::kSingle) {
        intersect_any_packets(bvh, leaves, rays, count, blocked, int(kernel));
      } else {
        intersect_any(bvh, leaves, rays, count, blocked);
      }
    });
  } else {
    std::fill(blocked, blocked + count, uint8_t(0));
  }
  if (quadric_count() == 0) return;
  for (size_t i = 0; i < count; ++i) {
    if (blocked[i]) continue;
    blocked[i] = quadric_bvh_.occluded(ray_at(rays, i), [&](uint32_t q, const Ray& ray) {
      float t;
      Vec2f uv;
      return torte::intersect((*quadrics_)[q], ray, &t, &uv);
    });
  }
}

size_t ShapeSet::accel_bytes() const {
  return tri_bvh_.memory_bytes() + tri_leaves_.memory_bytes() + ctri_bvh_.memory_bytes() +
         ptri_leaves_.memory_bytes() + quadric_bvh_.nodes().size() * sizeof(Bvh2Node) +
         quadric_bvh_.prim_indices().size() * sizeof(uint32_t) +
         tri_ref_.size() * sizeof(uint32_t) + mesh_first_.size() * sizeof(uint32_t);
}

SurfaceHit ShapeSet::surface(const Hit& hit, uint32_t object_base) const {
  // Each branch returns the reconstruction itself (no copy of the 80-byte hit on the way out: per hit, copies
  // through the levels of Scene::surface cost more than the arithmetic).
  if (hit.prim >= triangle_count())
    return quadric_surface((*quadrics_)[hit.prim - triangle_count()], Vec2f(hit.b1, hit.b2),
                           object_base + local_object_of(hit.prim));
  // Positions from the leaves (the meshes may have released theirs, scene/scene.h); normals and uvs from the
  // mesh, whose triangles are in leaf order.
  const TriangleRef ref = triangle_ref(hit.prim);
  const TriangleMesh& mesh = (*meshes_)[ref.mesh];
  Vec3f p[3];
  if (layout_ == BvhLayout::kDefault) {
    tri_leaves_.triangle(hit.prim, p);
  } else {
    ptri_leaves_.triangle(hit.prim, p);
  }
  return triangle_surface(mesh, mesh.triangle(ref.local), p, hit.b1, hit.b2, object_base + ref.mesh);
}

}  // namespace torte
