// Mesh-scale checks of the wide BVH build: node and leaf bytes on the 100k-triangle dragon (the whole budget, issue
// "SIMD core", is measured on a finished scene in test_geometry_set.cc), traversal on a real mesh, and two
// hidden reports run by hand:
//   torte_tests "[.bvh_report]"   bytes per triangle and SAH cost by node width, leaf size and block size
//   torte_tests "[.bvh_speed]"    build speed (Mtri/s) at 1 and 2 threads, dragon and a 1M-triangle mesh
#include <catch2/catch.hpp>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "accel/bvh2.h"
#include "accel/bvh_build.h"
#include "accel/wide_bvh_reference.h"
#include "core/rng.h"
#include "geometry/mesh.h"
#include "geometry/mesh_io.h"

using namespace torte;

namespace {

const std::string kDragon = std::string(TORTE_SHARED_DATA) + "/meshes/dragon/dragon_100k_binary_le.ply";

// The dragon through the product's loader; false if the shared data is absent.
bool read_ply(const std::string& path, TriangleMesh* mesh) {
  if (!std::ifstream(path)) return false;
  *mesh = load_mesh(path);
  return true;
}

std::vector<Bounds3f> triangle_bounds(const TriangleMesh& m) {
  std::vector<Bounds3f> b(m.triangle_count());
  for (size_t t = 0; t < b.size(); ++t) b[t] = m.triangle_bounds(t);
  return b;
}

// A bumpy sphere of 2 * rows * cols triangles: mesh-like (connected, varied sizes), unlike random soup.
TriangleMesh bumpy_sphere(int rows, int cols) {
  TriangleMesh m;
  for (int i = 0; i <= rows; ++i) {
    const float theta = kPi * float(i) / float(rows);
    for (int j = 0; j < cols; ++j) {
      const float phi = 2 * kPi * float(j) / float(cols);
      const float r = 1 + 0.05f * std::sin(7 * phi) * std::sin(5 * theta) + 0.02f * std::sin(40 * phi + 30 * theta);
      m.add_vertex(Vec3f(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)) * r);
    }
  }
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const uint32_t a = uint32_t(i * cols + j), b = uint32_t(i * cols + (j + 1) % cols);
      m.add_triangle(a, b + uint32_t(cols), b);
      m.add_triangle(a, a + uint32_t(cols), b + uint32_t(cols));
    }
  return m;
}

// Bytes per triangle for the scene's share of a mesh once the BVH owns the positions: indices (12 per
// triangle) and vertex normals (12 per vertex); GeometrySet drops prim_indices (meshes in leaf order) and the
// scene the positions (test_geometry_set.cc measures the finished scene).
double mesh_bytes_per_tri(const TriangleMesh& m) {
  return (12.0 * double(m.triangle_count()) + (m.has_normals() ? 12.0 * double(m.vertex_count()) : 0.0)) /
         double(m.triangle_count());
}

// One row of the memory report; `binary_block` > 0 builds the binary tree with that SAH block size instead
// (finer binary leaves for the collapse to merge).
template <int N>
void report_row(const std::vector<Bounds3f>& prims, const TriangleMesh& mesh, const BvhBuildOptions& o,
                int binary_block = 0) {
  const double n = double(prims.size());
  BvhBuildOptions bo = o;
  if (binary_block > 0) bo.leaf_block_size = binary_block;
  const WideBvh<N> bvh = collapse<N>(build_binary_bvh(prims, bo), o);
  const BvhStats s = bvh_stats(bvh);
  const TriangleLeaves leaves = make_triangle_leaves(bvh, mesh);
  const double nodes = double(s.node_bytes) / n, leaf = double(leaves.memory_bytes()) / n;
  std::printf("  N=%d leaf<=%-2d block %d%s%s | nodes %5.2f  leaves %5.2f  prim_idx %4.2f | total %5.2f"
              " | avg leaf %4.2f  fill %4.2f/%d  depth %2d  SAH %6.2f\n",
              N, o.max_leaf_size, o.leaf_block_size, o.collapse == CollapseMode::LargestArea ? " greedy" : "",
              binary_block > 0 ? " bin1" : "", nodes, leaf, double(s.index_bytes) / n,
              nodes + leaf + mesh_bytes_per_tri(mesh), s.avg_leaf_size, s.avg_children, N, s.max_depth,
              sah_cost(bvh, BvhBuildOptions{.leaf_block_size = 4}));
}

}  // namespace

TEST_CASE("bvh_build: dragon nodes and leaves fit the budget and trace like the reference BVH2", "[bvh_build]") {
  TriangleMesh mesh;
  if (!read_ply(kDragon, &mesh)) {
    WARN("skipped: " << kDragon << " is absent (shared data not installed)");
    return;
  }
  REQUIRE(mesh.triangle_count() == 100000);
  REQUIRE(mesh.vertex_count() == 50002);
  const std::vector<Bounds3f> prims = triangle_bounds(mesh);
  const WideBvh<kDefaultBvhWidth> bvh = build_wide_bvh<kDefaultBvhWidth>(prims);
  const TriangleLeaves leaves = make_triangle_leaves(bvh, mesh);
  const BvhStats s = bvh_stats(bvh);
  const double n = double(mesh.triangle_count());
  // Nodes, leaf triangles and the mesh's share as a renderer stores them (no prim_indices, no positions); the
  // finished scene's real allocation is checked in test_geometry_set.cc.
  const double total = (double(s.node_bytes) + double(leaves.memory_bytes())) / n + mesh_bytes_per_tri(mesh);
  INFO("nodes " << double(s.node_bytes) / n << " B/tri, leaves " << double(leaves.memory_bytes()) / n
                << " B/tri, mesh " << mesh_bytes_per_tri(mesh) << " B/tri, total " << total);
  CHECK(s.primitives == mesh.triangle_count());
  CHECK(double(s.node_bytes) / n <= 10.0);
  CHECK(total <= 64.0);

  // Closest hits agree with the reference BVH2 over the original mesh, rays aimed at the model.
  Bvh2 ref;
  ref.build(prims);
  const Bounds3f b = bvh.bounds;
  Pcg32 rng(21);
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3f target = b.lo + mul(b.diagonal(), Vec3f(rng.next_float(), rng.next_float(), rng.next_float()));
    const Vec3f o = b.center() + normalize(Vec3f(rng.next_float() - 0.5f, rng.next_float() - 0.5f,
                                                 rng.next_float() - 0.5f)) * length(b.diagonal());
    const Ray ray{o, normalize(target - o)};
    Ray rr = ray;
    uint32_t ref_prim = kNoHit;
    ref.intersect(rr, [&](uint32_t p, Ray& r) {
      TriangleHit th;
      const uint32_t* t = &mesh.indices[3 * size_t(p)];
      if (!intersect_triangle(r, mesh.position(t[0]), mesh.position(t[1]), mesh.position(t[2]), &th)) return false;
      r.t_max = th.t;
      ref_prim = p;
      return true;
    });
    const Hit h = wide_closest_hit_reference(bvh, leaves, ray);
    REQUIRE((h.prim == kNoHit) == (ref_prim == kNoHit));
    CHECK(wide_any_hit_reference(bvh, leaves, ray) == (ref_prim != kNoHit));
    if (h.prim == kNoHit) continue;
    ++hits;
    CHECK(h.t == rr.t_max);
  }
  CHECK(hits > 1000);
}

TEST_CASE("bvh_build: bytes per triangle report", "[.bvh_report]") {
  TriangleMesh mesh;
  if (!read_ply(kDragon, &mesh)) {
    WARN("skipped: " << kDragon << " is absent");
    return;
  }
  const std::vector<Bounds3f> prims = triangle_bounds(mesh);
  std::printf("dragon, %zu triangles, bytes per triangle. total = nodes + leaves + mesh share %.2f (indices +\n"
              "normals; prim_indices dropped). SAH: traversal 1, intersection 1 per block of 4. bin1: binary tree\n"
              "built with block 1, collapsed with the row's block. greedy: largest-area collapse.\n",
              mesh.triangle_count(), mesh_bytes_per_tri(mesh));
  for (int leaf : {4, 8, 16})
    for (int block : {1, 4, 8}) {
      if (block > leaf) continue;
      const BvhBuildOptions o{.max_leaf_size = leaf, .leaf_block_size = block};
      report_row<4>(prims, mesh, o);
      report_row<8>(prims, mesh, o);
      if (block == 1) continue;
      report_row<8>(prims, mesh, o, 1);
      BvhBuildOptions greedy = o;
      greedy.collapse = CollapseMode::LargestArea;
      report_row<4>(prims, mesh, greedy);
      report_row<8>(prims, mesh, greedy);
    }
}

TEST_CASE("bvh_build: build speed report", "[.bvh_speed]") {
  auto measure = [](const char* name, const TriangleMesh& mesh) {
    const std::vector<Bounds3f> prims = triangle_bounds(mesh);
    for (int threads : {1, 2}) {
      tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(threads));
      std::vector<double> ms_bvh, ms_all, cpu_ms;
      for (int rep = 0; rep < 5; ++rep) {
        const std::clock_t c0 = std::clock();
        const auto t0 = std::chrono::steady_clock::now();
        const WideBvh<kDefaultBvhWidth> bvh = build_wide_bvh<kDefaultBvhWidth>(prims);
        const auto t1 = std::chrono::steady_clock::now();
        const TriangleLeaves leaves = make_triangle_leaves(bvh, mesh);
        const auto t2 = std::chrono::steady_clock::now();
        cpu_ms.push_back(1e3 * double(std::clock() - c0) / CLOCKS_PER_SEC);
        ms_bvh.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
        ms_all.push_back(std::chrono::duration<double, std::milli>(t2 - t0).count());
        CHECK(leaves.size() == mesh.triangle_count());
      }
      std::sort(ms_bvh.begin(), ms_bvh.end());
      std::sort(ms_all.begin(), ms_all.end());
      std::sort(cpu_ms.begin(), cpu_ms.end());
      const double n = double(mesh.triangle_count());
      // CPU time of the whole process: with other processes on the machine, the 1-thread CPU time is the
      // better estimate of an idle machine's wall time.
      std::printf("%-14s %8zu tris, %d thread(s): BVH%d %7.1f ms (%5.2f Mtri/s), +leaves %7.1f ms (%5.2f Mtri/s)"
                  "  [wall, median of 5; min %.1f ms; CPU %.1f ms]\n",
                  name, mesh.triangle_count(), threads, kDefaultBvhWidth, ms_bvh[2], n / ms_bvh[2] / 1e3, ms_all[2],
                  n / ms_all[2] / 1e3, ms_bvh[0], cpu_ms[2]);
    }
  };
  TriangleMesh dragon;
  if (read_ply(kDragon, &dragon)) measure("dragon", dragon);
  else WARN("dragon skipped: " << kDragon << " is absent");
  measure("bumpy sphere", bumpy_sphere(500, 1000));
}
