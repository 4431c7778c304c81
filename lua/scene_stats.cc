#include "scene_stats.h"

#include <chrono>
#include <cstdio>
#include <unordered_set>

#include "accel/bvh_build.h"
#include "accel/wide_bvh.h"
#include "binding.h"
#include "core/memory_budget.h"
#include "progress.h"
#include "scene/builder.h"
#include "types.h"

namespace torte::lua {

namespace {

double half_area(const Bounds3f& b) {
  const Vec3f d = b.hi - b.lo;
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

// Child c's box: as stored, or dequantised.
template <int N>
Bounds3f child_bounds(const WideNode<N>& n, int c) {
  return {{n.lo_x[c], n.lo_y[c], n.lo_z[c]}, {n.hi_x[c], n.hi_y[c], n.hi_z[c]}};
}
Bounds3f child_bounds(const QuantNode& n, int c) {
  return {{dequantize(n, 0, n.q[0][c]), dequantize(n, 1, n.q[1][c]), dequantize(n, 2, n.q[2][c])},
          {dequantize(n, 0, n.q[3][c]), dequantize(n, 1, n.q[4][c]), dequantize(n, 2, n.q[5][c])}};
}

// Depth, leaves and SAH cost of a wide BVH (either layout) by one walk over its nodes (child bounds live in the
// parent).
template <class Tree>
void tree_statistics(const Tree& bvh, SceneStatistics* s) {
  constexpr int N = Tree::kWidth;
  if (bvh.nodes.empty()) return;
  const double root_area = std::max(double(half_area(bvh.bounds)), 1e-30);
  struct Entry {
    uint32_t node, depth;
    double area;
  };
  std::vector<Entry> stack{{0, 1, root_area}};
  while (!stack.empty()) {
    const Entry e = stack.back();
    stack.pop_back();
    s->depth = std::max(s->depth, e.depth);
    s->sah_cost += e.area / root_area;  // visiting the node tests its N children at once
    const auto& n = bvh.nodes[e.node];
    for (int c = 0; c < N; ++c) {
      if (n.child[c] == kEmptyChild) continue;
      const Bounds3f b = child_bounds(n, c);
      if (is_leaf_child(n.child[c])) {
        ++s->leaves;
        s->sah_cost += half_area(b) / root_area * n.leaf_count[c];
      } else {
        stack.push_back({n.child[c], e.depth + 1, half_area(b)});
      }
    }
  }
}

}  // namespace

SceneStatistics scene_statistics(const Scene& scene, double build_seconds, bool reused) {
  SceneStatistics s;
  s.primitives = scene.primitive_count();
  s.triangles = scene.triangle_count();
  s.instances = scene.instances.size();
  s.groups = scene.instances.empty() ? 0 : scene.prototypes.size();
  for (const Instance& inst : scene.instances)
    s.placed_primitives += scene.prototypes[inst.prototype]->geometry.primitive_count();
  s.lights = scene.lights.size();
  const ShapeSet::TriangleMemory m = scene.accel().root().triangle_memory();
  s.layout = bvh_layout_name(scene.accel().layout());
  if (scene.accel().root().layout() == BvhLayout::kCompact) {
    s.nodes = scene.accel().root().compact_bvh().nodes.size();
    tree_statistics(scene.accel().root().compact_bvh(), &s);
  } else {
    s.nodes = scene.accel().root().triangle_bvh().nodes.size();
    tree_statistics(scene.accel().root().triangle_bvh(), &s);
  }
  const GeometrySet& root = scene.accel().root();
  s.voxel_grids = root.grid_count();
  for (uint32_t g = 0; g < root.grid_count(); ++g) {
    s.voxel_nodes += root.grid(g)->tree->nodes().size();
    s.voxels += root.grid(g)->tree->stats().voxels;
  }
  uint64_t voxel_bytes = 0;
  for (uint32_t g = 0; g < root.grid_count(); ++g) voxel_bytes += root.grid(g)->bytes();
  if (s.voxels > 0) s.voxel_bytes_per_voxel = double(voxel_bytes) / double(s.voxels);
  s.bounds = scene.accel().bounds();
  // Mesh triples and normals count each source once (as the render summary does).
  size_t indices = 0, normals = 0;
  std::unordered_set<const void*> seen;
  for (const TriangleMesh& mesh : scene.meshes) {
    normals += mesh.nx.size() * 3 * sizeof(float);
    if (seen.insert(&mesh.triple_array()).second) indices += mesh.triple_array().size() * sizeof(uint32_t);
  }
  if (s.triangles > 0) {
    const double t = double(s.triangles);
    s.node_bytes = double(m.nodes) / t;
    s.leaf_bytes = double(m.leaves) / t;
    s.index_bytes = double(indices) / t;
    s.map_bytes = double(m.index_map) / t;
    s.normal_bytes = double(normals) / t;
  }
  s.geometry_bytes = scene.geometry_bytes();
  s.accel_bytes = scene.accel_bytes();
  s.build_seconds = build_seconds;
  s.reused = reused;
  s.peak_memory = peak_resident_memory();
  return s;
}

std::string format_scene_statistics(const SceneStatistics& s) {
  char buf[512];
  std::string out = "scene statistics:\n";
  std::snprintf(buf, sizeof buf, "  primitives %llu (triangles %llu); %llu instances of %llu groups placing %llu; %llu lights\n",
                (unsigned long long)s.primitives, (unsigned long long)s.triangles, (unsigned long long)s.instances,
                (unsigned long long)s.groups, (unsigned long long)s.placed_primitives, (unsigned long long)s.lights);
  out += buf;
  std::snprintf(buf, sizeof buf, "  triangle BVH: %llu nodes of width %d, %llu leaves, depth %u, SAH cost %.1f; %s layout\n",
                (unsigned long long)s.nodes, kDefaultBvhWidth, (unsigned long long)s.leaves, s.depth, s.sah_cost,
                s.layout);
  out += buf;
  if (s.voxel_grids > 0) {
    std::snprintf(buf, sizeof buf, "  voxel grids: %llu, %llu kd-tree nodes, %llu solid voxels, %.2f bytes per voxel\n",
                  (unsigned long long)s.voxel_grids, (unsigned long long)s.voxel_nodes, (unsigned long long)s.voxels,
                  s.voxel_bytes_per_voxel);
    out += buf;
  }
  std::snprintf(buf, sizeof buf,
                "  bytes per triangle: nodes %.1f, leaves %.1f, indices %.1f, index map %.1f, normals %.1f; "
                "total %.1f\n",
                s.node_bytes, s.leaf_bytes, s.index_bytes, s.map_bytes, s.normal_bytes,
                s.node_bytes + s.leaf_bytes + s.index_bytes + s.map_bytes + s.normal_bytes);
  out += buf;
  std::snprintf(buf, sizeof buf, "  memory: geometry %s, acceleration %s; build %s%s; peak resident %s\n",
                format_bytes(s.geometry_bytes).c_str(), format_bytes(s.accel_bytes).c_str(),
                format_duration(s.build_seconds).c_str(), s.reused ? " (scene unchanged, reused)" : "",
                format_bytes(s.peak_memory).c_str());
  return out + buf;
}

int scene_stats(lua_State* L) {
  auto scene = to_object<SceneBuilder>(L, 1);
  if (!scene) throw Error("scene:stats must be called with ':' on a scene");
  const auto t0 = std::chrono::steady_clock::now();
  const SceneCache::Lookup built = cached_scene(L, *scene, "scene:stats");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const SceneStatistics s = scene_statistics(*built.scene, seconds, built.reused);
  lua_newtable(L);
  const auto set = [&](const char* key, double v) {
    lua_pushnumber(L, v);
    lua_setfield(L, -2, key);
  };
  const auto set_int = [&](const char* key, uint64_t v) {
    lua_pushinteger(L, lua_Integer(v));
    lua_setfield(L, -2, key);
  };
  set_int("primitives", s.primitives);
  set_int("triangles", s.triangles);
  set_int("instances", s.instances);
  set_int("groups", s.groups);
  set_int("placed_primitives", s.placed_primitives);
  set_int("lights", s.lights);
  lua_pushstring(L, s.layout);
  lua_setfield(L, -2, "layout");
  set_int("nodes", s.nodes);
  set_int("leaves", s.leaves);
  set_int("depth", s.depth);
  set("sah_cost", s.sah_cost);
  set_int("voxel_grids", s.voxel_grids);
  set_int("voxel_nodes", s.voxel_nodes);
  set_int("voxels", s.voxels);
  set("voxel_bytes_per_voxel", s.voxel_bytes_per_voxel);
  const auto push_vec = [&](Vec3f v) {
    lua_createtable(L, 3, 0);
    for (int i = 0; i < 3; ++i) {
      lua_pushnumber(L, v[i]);
      lua_rawseti(L, -2, i + 1);
    }
  };
  lua_createtable(L, 0, 2);
  push_vec(s.bounds.lo);
  lua_setfield(L, -2, "min");
  push_vec(s.bounds.hi);
  lua_setfield(L, -2, "max");
  lua_setfield(L, -2, "bounds");
  lua_newtable(L);
  set("nodes", s.node_bytes);
  set("leaves", s.leaf_bytes);
  set("indices", s.index_bytes);
  set("index_map", s.map_bytes);
  set("normals", s.normal_bytes);
  lua_setfield(L, -2, "bytes_per_triangle");
  set_int("geometry_bytes", s.geometry_bytes);
  set_int("accel_bytes", s.accel_bytes);
  set("build_seconds", s.build_seconds);
  lua_pushboolean(L, s.reused);
  lua_setfield(L, -2, "reused");
  set_int("peak_memory", s.peak_memory);
  return 1;
}

}  // namespace torte::lua
