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
  s.nodes = m.nodes / sizeof(WideNode<kDefaultBvhWidth>);
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
  std::snprintf(buf, sizeof buf, "  triangle BVH: %llu nodes of width %d\n", (unsigned long long)s.nodes,
                kDefaultBvhWidth);
  out += buf;
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
  set_int("nodes", s.nodes);
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
