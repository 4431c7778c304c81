// Benchmark workloads, defined once and shared by every variant (bench_traversal.cc, embree_compare.cc).
//
// A scene is a mesh (Stanford bunny or dragon, or the bunny grown by subdivision) inside a closed box of 12
// triangles, so rays leaving the mesh hit a wall. Three ray sets are generated from it, deterministically:
//   primary: 1024 x 1024 pinhole camera rays framing the mesh (camera inside the box), in coherent tiles:
//            8x8 pixel tiles, each split into four 4x4 blocks, each of those into two 4x2 halves, so every
//            aligned group of 16 consecutive rays is a 4x4 block of neighbouring pixels and of 8 a 4x2 block.
//   diffuse:  one cosine-distributed ray per primary hit, around the hit triangle's geometric normal (flipped to
//            face the camera ray), origin offset off the surface; incoherent, t_max = inf.
//   shadow:   one ray per primary hit towards a random point on a square area light just below the ceiling;
//            t_max stops at the light.
// Ground truth for every ray comes from the plain scalar reference (Bvh2 + intersect_triangle), computed once
// per scene; benchmarks compare their own results against it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "accel/bvh2.h"
#include "accel/bvh_build.h"
#include "accel/hit.h"
#include "accel/wide_bvh.h"
#include "core/ray.h"
#include "geometry/mesh.h"

namespace torte::bench {

// ---- data location and run size -------------------------------------------------------------------------------

// ../shared/data relative to the source dir (compile definition TORTE_SHARED_DATA), or $TORTE_SHARED_DATA.
std::string shared_data_dir();
// True if the meshes are there; otherwise *why says what is missing.
bool shared_data_available(std::string* why);
// Full run: adds bunny-4m and bunny-16m. Enabled by the environment variable TORTE_BENCH_FULL=1 (or by the
// programs' --full flag, which calls set_full_run).
bool full_run();
void set_full_run(bool full);
// Scenes of a run: bunny, dragon, bunny-1m (+ bunny-4m, bunny-16m when full). $TORTE_BENCH_SCENES
// (comma-separated) overrides the list.
std::vector<std::string> scene_names();
// Image resolution of the primary rays: 1024, or $TORTE_BENCH_RES (for quick development runs only).
int image_resolution();

// ---- rays ------------------------------------------------------------------------------------------------------

using RayBatch = RayArrays;  // accel/hit.h

// Ground truth of a workload, from the scalar reference.
struct Reference {
  std::vector<float> t;           // closest hit distance, kInfinity for a miss
  std::vector<uint8_t> occluded;  // anything in (0, t_max)
  size_t hits = 0, occluded_count = 0;
  double sum_t = 0;               // over hits
};

struct Workload {
  std::string name;  // "primary", "diffuse", "shadow"
  RayBatch rays;
  Reference ref;
};

// Result of checking a variant's output against a Reference.
struct Check {
  size_t rays = 0, mismatches = 0;  // hit/miss (or occluded) disagreements, or t off by more than the tolerance
  size_t hits = 0;                  // hits (or occluded rays) reported by the variant
  double sum_t = 0;                 // over the variant's hits
  double mismatch_fraction() const { return rays ? double(mismatches) / double(rays) : 0; }
};
Check check_closest(const Reference& ref, const float* t, size_t n, float rel_tol);
Check check_closest(const Reference& ref, const Hit* hits, size_t n, float rel_tol);
Check check_any(const Reference& ref, const uint8_t* occluded, size_t n);

// ---- scenes ----------------------------------------------------------------------------------------------------

// torte's wide BVH over a mesh with its leaf-order triangles: what the SIMD kernels take.
template <int N>
struct TorteAccel {
  WideBvh<N> bvh;
  TriangleLeaves leaves;
  size_t bytes() const { return bvh.memory_bytes() + leaves.memory_bytes(); }  // nodes + prim_indices + leaves
};
// The whole torte build as the renderer does it: triangle bounds (TBB), binned-SAH build + collapse, leaves.
// Parallelism follows the active tbb::global_control / arena.
template <int N>
TorteAccel<N> build_torte(const TriangleMesh& mesh, const BvhBuildOptions& options = {});
std::vector<Bounds3f> triangle_bounds(const TriangleMesh& mesh);

struct BenchScene {
  std::string name;
  TriangleMesh mesh;           // the model's triangles, then the 12 box triangles
  size_t model_triangles = 0;  // the model alone
  Bvh2 bvh2;                   // scalar reference over mesh (original triangle numbering)
  Workload primary, diffuse, shadow;
  double load_seconds = 0, setup_seconds = 0;

  size_t triangles() const { return mesh.triangle_count(); }
  const Workload& workload(const std::string& name) const;
  // torte's wide BVHs at the default build options, built on first use (N = 4 or 8).
  const TorteAccel<4>& wide4() const;
  const TorteAccel<8>& wide8() const;

  // Scalar reference queries (plain C++ Bvh2 traversal, watertight triangle test through the index buffer).
  Hit reference_closest(const Ray& ray) const;  // Hit::prim = original triangle index
  bool reference_any(const Ray& ray) const;

 private:
  mutable std::unique_ptr<TorteAccel<4>> wide4_;
  mutable std::unique_ptr<TorteAccel<8>> wide8_;
};

// Loads (and subdivides) the scene's mesh, adds the box and generates the three workloads with their ground
// truth. Only the most recently requested scene stays cached, so that the 16 M-triangle scenes fit in memory.
// Throws torte::Error for an unknown name or an unreadable mesh.
const BenchScene& get_scene(const std::string& name);
// The same for a user's mesh: the .ply or .obj file at `path` (torte's readers, load_mesh), subdivided `grow`
// times as the bunny-Nm scenes are (1-to-4, the same displacement and seed), in the same box with the same
// framing, camera and light. The scene is named after the file ("lucy_100k.obj", "lucy_100k.obj-grow2").
// Shares the one-scene cache with get_scene. Throws torte::Error for an unreadable or bad file.
const BenchScene& get_mesh_scene(const std::string& path, int grow = 0);
void release_scene();

}  // namespace torte::bench
