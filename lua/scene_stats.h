// Statistics of a built scene: what --stats prints after each build and scene:stats() returns (triangles,
// BVH nodes, bytes per triangle (nodes, leaves, ...) by part, build time, peak memory).
#pragma once
#include <lua.h>

#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace torte::lua {

struct SceneStatistics {
  uint64_t primitives = 0, triangles = 0;    // of the top-level geometry (instances' prototypes not counted)
  uint64_t instances = 0, groups = 0, placed_primitives = 0;  // instancing: what the instances place
  uint64_t lights = 0;
  const char* layout = "default";            // the triangles' layout: "default" or "compact" (accel_options.h)
  uint64_t nodes = 0;                        // wide nodes of the top-level triangle BVH
  uint64_t leaves = 0;                       // its leaves (triangle groups)
  uint32_t depth = 0;                        // its depth in nodes (a root alone: 1)
  // Its surface-area cost, traversal and triangle tests weighted 1 each: the expected node visits plus triangle
  // tests of a random ray through the scene's bounds (MacDonald and Booth 1990, one node visit per wide node).
  double sah_cost = 0;
  // Voxel grids of the top level: how many, their kd-tree nodes, solid voxels, bytes per voxel of the trees.
  uint64_t voxel_grids = 0, voxel_nodes = 0, voxels = 0;
  double voxel_bytes_per_voxel = 0;
  Bounds3f bounds;                           // of everything the scene places
  // Bytes per top-level triangle: wide nodes, leaf vertices, mesh indices (each source once), the index map
  // from leaf order to meshes, vertex normals.
  double node_bytes = 0, leaf_bytes = 0, index_bytes = 0, map_bytes = 0, normal_bytes = 0;
  uint64_t geometry_bytes = 0, accel_bytes = 0;
  double build_seconds = 0;    // the build these statistics follow (~0 when the scene cache reused it)
  bool reused = false;
  uint64_t peak_memory = 0;    // peak resident bytes of the process so far
};

/// The statistics of `scene`, built in `build_seconds` (or reused from the scene cache).
SceneStatistics scene_statistics(const Scene& scene, double build_seconds, bool reused);
/// Several lines ("scene statistics: ..."), each ending with '\n', for --stats.
std::string format_scene_statistics(const SceneStatistics& s);
/// scene:stats(): builds the scene (through the run's scene cache, so a render right after reuses it) and
/// returns the statistics as a table with the field names of SceneStatistics.
int scene_stats(lua_State* L);

}  // namespace torte::lua
