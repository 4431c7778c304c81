// Voxel grids (src/voxel): kd-tree build and traversal on a synthetic terrain, or on a real world.
//   voxel/build/<world>/<serial|parallel>                  VoxelTree::build, Mvoxels/s and bytes/voxel
//   voxel/build/<world>/threads:<1|2>                      the parallel build in a TBB arena of 1 or 2 threads
//   voxel/<primary|diffuse>/<closest|any>/<kd|dda>/<world> scalar traversal of every ray once per iteration
//   voxel/<primary|diffuse>/<closest|any>/packet<8|16>/<world>  the packet traversal (simd/voxel_packet.h)
// kd = the packed kd-tree (voxel/voxel_traverse.h), dda = the brute-force 3D-DDA over the sparse grid (the
// tests' reference; it looks every cell up in the chunk hash map). Rays: a 512x512 pinhole view over the
// terrain, ordered in 4x4 pixel tiles (a packet of 16 is one tile, of 8 half a tile: 4x2), then one
// cosine-distributed bounce from each primary hit (same order). The kd results are checked against the DDA, and
// the packet results against the single-ray ones, before timing. Single thread, CPU time.
//
// The synthetic terrain is 512 x 128 x 512 (stone, dirt, grass, caves, slab cells). Hook for real worlds:
// TORTE_BENCH_VOXEL_WORLD=<file> benchmarks a dump written by the Lua grid:save(path) (e.g. from
// scenes/minecraft.lua) instead.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "core/rng.h"
#include "voxel/voxel_traverse.h"
#include "voxel_packet.h"
#include "voxel_test_cells.h"

using namespace torte;

namespace {

using torte::test::SlabCells;

VoxelGrid make_terrain(int n, int height) {
  VoxelGrid g;
  std::vector<int16_t> ids(kVoxelChunkVoxels);
  for (int cz = 0; cz < n / 16; ++cz)
    for (int cx = 0; cx < n / 16; ++cx)
      for (int cy = 0; cy < height / 16; ++cy) {
        for (int y = 0; y < 16; ++y)
          for (int z = 0; z < 16; ++z)
            for (int x = 0; x < 16; ++x) {
              const int wx = cx * 16 + x, wy = cy * 16 + y, wz = cz * 16 + z;
              const int h = int(48 + 24 * std::sin(wx * 0.017) * std::cos(wz * 0.021) +
                                6 * std::sin(wx * 0.11 + wz * 0.07) + 2 * std::sin(wx * 0.53) * std::sin(wz * 0.47));
              int16_t id = 0;
              if (wy < h) {
                const bool cave = std::sin(wx * 0.1) * std::sin(wy * 0.13) * std::sin(wz * 0.09) > 0.55;
                id = cave ? 0 : wy == h - 1 ? 2 : wy >= h - 4 ? 3 : (((wx ^ wz ^ wy) & 63) == 0 ? 4 : 1);
              } else if (wy == h && ((wx * 7 + wz * 13) % 17) == 0) {
                id = -1;
              } else if (wy > h && wy < h + 5 && (wx % 37) == 5 && (wz % 41) == 7) {
                id = 5;  // tree trunks
              }
              ids[size_t(voxel_chunk_index(x, y, z))] = id;
            }
        g.set_chunk(cx, cy, cz, ids.data());
      }
  return g;
}

struct World {
  std::string name;
  VoxelGrid grid;
  std::shared_ptr<VoxelTree> tree;
  std::vector<Ray> primary, diffuse;
  std::string error;
};

World& world() {
  static World w = [] {
    World w;
    if (const char* path = std::getenv("TORTE_BENCH_VOXEL_WORLD")) {
      w.name = "world";
      w.grid = VoxelGrid::load(path);
    } else {
      w.name = "terrain512";
      w.grid = make_terrain(512, 128);
    }
    w.tree = std::make_shared<VoxelTree>(VoxelTree::build(w.grid));
    const Bounds3f b = w.tree->bounds();
    const Vec3f c = b.center(), ext = b.diagonal();
    // A view from above one side, looking down across the world.
    const Vec3f eye(c.x, b.lo.y + ext.y * 0.9f, b.lo.z - 0.1f * ext.z), target(c.x, b.lo.y + ext.y * 0.3f, c.z);
    const Vec3f fw = normalize(target - eye), right = normalize(cross(Vec3f(0, 1, 0), fw)), up = cross(fw, right);
    const int res = 512;
    for (int ty = 0; ty < res; ty += 4)
      for (int tx = 0; tx < res; tx += 4)
        for (int y = ty; y < ty + 4; ++y)
          for (int x = tx; x < tx + 4; ++x) {
            const float u = (x + 0.5f) / res * 2 - 1, v = 1 - (y + 0.5f) / res * 2;
            w.primary.push_back({eye, normalize(fw + right * (u * 0.6f) + up * (v * 0.6f))});
          }
    Pcg32 rng(7);
    int mismatches = 0;
    for (const Ray& r : w.primary) {
      VoxelHit h, ref;
      const bool hit = voxel_intersect(*w.tree, r, &h, SlabCells{});
      if (hit != voxel_intersect_dda(*w.tree, w.grid, r, &ref, SlabCells{}) || (hit && h.t != ref.t)) ++mismatches;
      if (!hit) continue;
      Vec3f n(0, 1, 0);
      if (h.face >= 0) {
        n = Vec3f(0, 0, 0);
        n[h.face / 2] = h.face % 2 == 0 ? 1.0f : -1.0f;
      }
      const Frame f = Frame::from_z(n);
      const float r1 = rng.next_float(), r2 = rng.next_float(), s = std::sqrt(r1), phi = 6.2831853f * r2;
      const Vec3f d = f.s * (s * std::cos(phi)) + f.t * (s * std::sin(phi)) + n * std::sqrt(std::max(0.0f, 1 - r1));
      w.diffuse.push_back({r.at(h.t) + n * 1e-3f, d});
    }
    for (const Ray& r : w.diffuse) {
      VoxelHit h, ref;
      const bool hit = voxel_intersect(*w.tree, r, &h, SlabCells{});
      const bool hit_ref = voxel_intersect_dda(*w.tree, w.grid, r, &ref, SlabCells{});
      if (hit != hit_ref || (hit && h.t != ref.t)) {
        if (mismatches < 4)
          std::fprintf(stderr, "voxel bench: kd %d t %g v %d %d %d f %d id %d | dda %d t %g v %d %d %d f %d id %d; o %.9g %.9g %.9g d %.9g %.9g %.9g\n",
                       hit, h.t, h.voxel[0], h.voxel[1], h.voxel[2], h.face, h.id, hit_ref, ref.t, ref.voxel[0],
                       ref.voxel[1], ref.voxel[2], ref.face, ref.id, r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z);
        ++mismatches;
      }
    }
    if (mismatches) w.error = std::to_string(mismatches) + " rays differ between the kd-tree and the DDA";
    // The packets against single rays.
    const SlabCells cells;
    for (const std::vector<Ray>* rays : {&w.primary, &w.diffuse})
      for (const int ps : {8, 16}) {
        std::vector<VoxelHit> hits(rays->size());
        std::vector<uint8_t> found(rays->size()), occ(rays->size());
        voxel_intersect_packets(*w.tree, rays->data(), rays->size(), hits.data(), found.data(), ps,
                                voxel_cell_callbacks(cells));
        voxel_occluded_packets(*w.tree, rays->data(), rays->size(), occ.data(), ps, voxel_cell_callbacks(cells));
        int differ = 0;
        for (size_t i = 0; i < rays->size(); ++i) {
          VoxelHit h;
          const bool hit = voxel_intersect(*w.tree, (*rays)[i], &h, cells);
          differ += hit != bool(found[i]) || occ[i] != voxel_occluded(*w.tree, (*rays)[i], cells) ||
                    (hit && (std::memcmp(&h.t, &hits[i].t, 4) != 0 || h.face != hits[i].face ||
                             h.id != hits[i].id || std::memcmp(&h.u, &hits[i].u, 4) != 0 ||
                             std::memcmp(&h.v, &hits[i].v, 4) != 0 || h.voxel[0] != hits[i].voxel[0] ||
                             h.voxel[1] != hits[i].voxel[1] || h.voxel[2] != hits[i].voxel[2]));
        }
        if (differ) w.error = std::to_string(differ) + " rays differ between packets of " + std::to_string(ps) +
                              " and single rays";
      }
    std::fprintf(stderr, "voxel bench: packet kernel target %s\n", voxel_packet_target_name());
    std::fprintf(stderr, "voxel bench world %s: %llu voxels, box %dx%dx%d, %llu nodes, %.3f bytes/voxel\n",
                 w.name.c_str(), static_cast<unsigned long long>(w.tree->stats().voxels), 1 << w.tree->log2_size()[0],
                 1 << w.tree->log2_size()[1], 1 << w.tree->log2_size()[2],
                 static_cast<unsigned long long>(w.tree->stats().nodes), w.tree->stats().bytes_per_voxel());
    return w;
  }();
  return w;
}

void BM_VoxelBuild(benchmark::State& state, bool parallel) {
  World& w = world();
  uint64_t voxels = 0;
  double bpv = 0;
  for (auto _ : state) {
    const VoxelTree t = VoxelTree::build(w.grid, parallel);
    voxels = t.stats().voxels;
    bpv = t.stats().bytes_per_voxel();
    benchmark::DoNotOptimize(t.nodes().data());
  }
  state.counters["Mvoxels/s"] =
      benchmark::Counter(double(voxels) * double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate);
  state.counters["bytes/voxel"] = bpv;
}

// The parallel build in an arena of `threads` threads (wall time).
void BM_VoxelBuildThreads(benchmark::State& state, int threads) {
  World& w = world();
  tbb::task_arena arena(threads);
  uint64_t voxels = 0;
  for (auto _ : state) {
    arena.execute([&] {
      const VoxelTree t = VoxelTree::build(w.grid, true);
      voxels = t.stats().voxels;
      benchmark::DoNotOptimize(t.nodes().data());
    });
  }
  state.counters["Mvoxels/s"] =
      benchmark::Counter(double(voxels) * double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate);
}

template <bool kAny>
void BM_VoxelPacket(benchmark::State& state, bool diffuse, int packet_size) {
  World& w = world();
  if (!w.error.empty()) {
    state.SkipWithError(w.error.c_str());
    return;
  }
  const std::vector<Ray>& rays = diffuse ? w.diffuse : w.primary;
  const SlabCells cells;
  const VoxelCellCallbacks cb = voxel_cell_callbacks(cells);
  std::vector<VoxelHit> hits(rays.size());
  std::vector<uint8_t> found(rays.size());
  size_t n = 0;
  for (auto _ : state) {
    if constexpr (kAny)
      voxel_occluded_packets(*w.tree, rays.data(), rays.size(), found.data(), packet_size, cb);
    else
      voxel_intersect_packets(*w.tree, rays.data(), rays.size(), hits.data(), found.data(), packet_size, cb);
    benchmark::DoNotOptimize(found.data());
    n = 0;
    for (uint8_t f : found) n += f;
  }
  state.counters["Mrays/s"] =
      benchmark::Counter(double(rays.size()) * double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate);
  state.counters["hit%"] = 100.0 * double(n) / double(rays.size());
}

template <bool kAny, bool kDda>
void BM_VoxelTrace(benchmark::State& state, bool diffuse) {
  World& w = world();
  if (!w.error.empty()) {
    state.SkipWithError(w.error.c_str());
    return;
  }
  const std::vector<Ray>& rays = diffuse ? w.diffuse : w.primary;
  size_t hits = 0;
  for (auto _ : state) {
    hits = 0;
    for (const Ray& r : rays) {
      VoxelHit h;
      bool hit;
      if constexpr (kDda) {
        hit = kAny ? voxel_occluded_dda(*w.tree, w.grid, r, SlabCells{}) : voxel_intersect_dda(*w.tree, w.grid, r, &h, SlabCells{});
      } else {
        hit = kAny ? voxel_occluded(*w.tree, r, SlabCells{}) : voxel_intersect(*w.tree, r, &h, SlabCells{});
      }
      hits += hit;
    }
    benchmark::DoNotOptimize(hits);
  }
  state.counters["Mrays/s"] =
      benchmark::Counter(double(rays.size()) * double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate);
  state.counters["hit%"] = 100.0 * double(hits) / double(rays.size());
}

[[maybe_unused]] const bool registered = [] {
  const std::string n = std::getenv("TORTE_BENCH_VOXEL_WORLD") ? "world" : "terrain512";
  benchmark::RegisterBenchmark(("voxel/build/" + n + "/serial").c_str(), BM_VoxelBuild, false)
      ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
  benchmark::RegisterBenchmark(("voxel/build/" + n + "/parallel").c_str(), BM_VoxelBuild, true)
      ->Unit(benchmark::kMillisecond)->UseRealTime();
  for (const int threads : {1, 2})
    benchmark::RegisterBenchmark(("voxel/build/" + n + "/threads:" + std::to_string(threads)).c_str(),
                                 BM_VoxelBuildThreads, threads)
        ->Unit(benchmark::kMillisecond)->UseRealTime();
  for (const bool diffuse : {false, true}) {
    const std::string w = diffuse ? "diffuse" : "primary";
    benchmark::RegisterBenchmark(("voxel/" + w + "/closest/kd/" + n).c_str(), BM_VoxelTrace<false, false>, diffuse)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("voxel/" + w + "/any/kd/" + n).c_str(), BM_VoxelTrace<true, false>, diffuse)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("voxel/" + w + "/closest/dda/" + n).c_str(), BM_VoxelTrace<false, true>, diffuse)
        ->Unit(benchmark::kMillisecond);
    for (const int ps : {8, 16}) {
      const std::string p = "/packet" + std::to_string(ps) + "/";
      benchmark::RegisterBenchmark(("voxel/" + w + "/closest" + p + n).c_str(), BM_VoxelPacket<false>, diffuse, ps)
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("voxel/" + w + "/any" + p + n).c_str(), BM_VoxelPacket<true>, diffuse, ps)
          ->Unit(benchmark::kMillisecond);
    }
  }
  return true;
}();

}  // namespace
