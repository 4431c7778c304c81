// Google Benchmark cases for torte's acceleration structures on the shared workloads (workloads.h):
//   <scene>/build/<accel>/threads:<t>                 build (bounds + SAH build + collapse + leaves), Mtris/s
//   <scene>/<workload>/<query>/<accel>/<mode>         trace every ray of the workload once per iteration, Mrays/s
// with <accel> = wide4, wide8 (SIMD kernels, simd/traverse.h) or bvh2 (the plain C++ scalar reference, single
// rays only), <query> = closest or any, <mode> = single, packet8 or packet16, <workload> = primary, diffuse or
// shadow. Every case checks its own results against the scalar reference (computed once per scene) and fails
// with SkipWithError when they disagree, so a fast wrong kernel cannot look good.
//
// Clocks: traversal runs on one thread and is timed in that thread's CPU time; one-thread builds in the process's
// CPU time; two-thread builds in wall time (names end in /process_time or /real_time). Mrays/s and Mtris/s follow
// the same clock. The machine is shared, and CPU time does not count the time other processes take the core.
//
// Own flags (after Google Benchmark's): --full adds the 4 M and 16 M triangle bunnies (or TORTE_BENCH_FULL=1).
// Environment: TORTE_BENCH_SCENES=bunny,dragon picks scenes; TORTE_BENCH_RES=256 shrinks the image (development
// only; results quoted in RESULTS.md use the default 1024).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "accel/wide_bvh_reference.h"
#include "traverse.h"
#include "workloads.h"

using namespace torte;
using namespace torte::bench;

namespace {

// Traversal results must equal the scalar reference's (the tests' tolerance): same hit or miss, t within 1e-5
// relative. A handful of disagreements per million rays is tolerated (equal-t ties on shared edges report the
// same t, so in practice the count is 0); more fails the case.
constexpr float kRelTol = 1e-5f;
constexpr double kMaxMismatchFraction = 1e-5;

enum class Query { Closest, Any };
enum class Accel { Bvh2, Wide4, Wide8 };
enum class Mode { Single, Packet8, Packet16 };

const char* name_of(Query q) { return q == Query::Closest ? "closest" : "any"; }
const char* name_of(Accel a) { return a == Accel::Bvh2 ? "bvh2" : a == Accel::Wide4 ? "wide4" : "wide8"; }
const char* name_of(Mode m) { return m == Mode::Single ? "single" : m == Mode::Packet8 ? "packet8" : "packet16"; }

template <int N>
void trace_wide(const TorteAccel<N>& a, const RayBatch& rays, Query q, Mode m, Hit* hits, uint8_t* occluded) {
  const RaySoA soa = rays.soa();
  const size_t n = rays.size();
  if (m == Mode::Single) {
    if (q == Query::Closest) intersect_closest(a.bvh, a.leaves, soa, n, hits);
    else intersect_any(a.bvh, a.leaves, soa, n, occluded);
  } else {
    const int p = m == Mode::Packet8 ? 8 : 16;
    if (q == Query::Closest) intersect_closest_packets(a.bvh, a.leaves, soa, n, hits, p);
    else intersect_any_packets(a.bvh, a.leaves, soa, n, occluded, p);
  }
}

void trace_bvh2(const BenchScene& s, const RayBatch& rays, Query q, Hit* hits, uint8_t* occluded) {
  const size_t n = rays.size();
  if (q == Query::Closest) {
    for (size_t i = 0; i < n; ++i) hits[i] = s.reference_closest(rays.ray(i));
  } else {
    for (size_t i = 0; i < n; ++i) occluded[i] = s.reference_any(rays.ray(i));
  }
}

void BM_Trace(benchmark::State& state, std::string scene, std::string workload, Query q, Accel a, Mode m) {
  const BenchScene* s;
  try {
    s = &get_scene(scene);
    if (a == Accel::Wide4) s->wide4();  // build outside the timed loop
    if (a == Accel::Wide8) s->wide8();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const Workload& w = s->workload(workload);
  const size_t n = w.rays.size();
  std::vector<Hit> hits(q == Query::Closest ? n : 0);
  std::vector<uint8_t> occluded(q == Query::Any ? n : 0);
  for (auto _ : state) {
    switch (a) {
      case Accel::Bvh2: trace_bvh2(*s, w.rays, q, hits.data(), occluded.data()); break;
      case Accel::Wide4: trace_wide(s->wide4(), w.rays, q, m, hits.data(), occluded.data()); break;
      case Accel::Wide8: trace_wide(s->wide8(), w.rays, q, m, hits.data(), occluded.data()); break;
    }
    benchmark::ClobberMemory();
  }
  const Check c = q == Query::Closest ? check_closest(w.ref, hits.data(), n, kRelTol)
                                      : check_any(w.ref, occluded.data(), n);
  state.counters["Mrays"] = benchmark::Counter(double(n) * double(state.iterations()) * 1e-6,
                                               benchmark::Counter::kIsRate);
  state.counters["rays"] = double(n);
  state.counters["hit%"] = 100.0 * double(c.hits) / double(n);
  state.counters["mismatch"] = double(c.mismatches);
  if (c.mismatch_fraction() > kMaxMismatchFraction) {
    char msg[256];
    std::snprintf(msg, sizeof msg,
                  "WRONG RESULTS: %zu of %zu rays disagree with the scalar reference (hits %zu vs %zu, sum t %.6g "
                  "vs %.6g)",
                  c.mismatches, n, c.hits, q == Query::Closest ? w.ref.hits : w.ref.occluded_count, c.sum_t,
                  w.ref.sum_t);
    state.SkipWithError(msg);
  }
}

// A build is checked by tracing a sample of the primary rays through it with the scalar wide-BVH reference
// (independent of the SIMD kernels), against the Bvh2 ground truth.
template <int N>
size_t check_build(const BenchScene& s, const TorteAccel<N>& a) {
  const Workload& w = s.primary;
  size_t bad = 0;
  for (size_t i = 0; i < w.rays.size(); i += 61) {
    const Hit h = wide_closest_hit_reference(a.bvh, a.leaves, w.rays.ray(i));
    const float r = w.ref.t[i];
    if ((h.prim != kNoHit) != (r < kInfinity) || (r < kInfinity && std::fabs(h.t - r) > kRelTol * r)) ++bad;
  }
  return bad;
}

template <int N>
void BM_BuildWide(benchmark::State& state, std::string scene, int threads) {
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(threads));
  const BenchScene* s;
  try {
    s = &get_scene(scene);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  std::optional<TorteAccel<N>> a;
  for (auto _ : state) {
    state.PauseTiming();
    a.reset();  // freeing the previous tree is not part of the build
    state.ResumeTiming();
    a.emplace(build_torte<N>(s->mesh));
    benchmark::DoNotOptimize(a->bvh.nodes.data());
  }
  const double tris = double(s->triangles());
  const size_t mesh_bytes = s->mesh.vertex_count() * 12 + s->mesh.indices.size() * 4;
  const BvhStats st = bvh_stats(a->bvh);
  state.counters["Mtris"] = benchmark::Counter(tris * double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate);
  state.counters["B/tri"] = double(a->bytes()) / tris;  // nodes + prim_indices + leaf triangles
  state.counters["B/tri+mesh"] = double(a->bytes() + mesh_bytes) / tris;
  state.counters["node_B/tri"] = double(st.node_bytes) / tris;
  state.counters["SAH"] = sah_cost(a->bvh);
  state.counters["leaf_size"] = st.avg_leaf_size;
  state.counters["children"] = st.avg_children;
  state.counters["tris"] = tris;
  if (const size_t bad = check_build(*s, *a)) {
    state.SkipWithError(("WRONG TREE: " + std::to_string(bad) + " sampled primary rays disagree with the reference")
                            .c_str());
  }
}

void BM_BuildBvh2(benchmark::State& state, std::string scene) {
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
  const BenchScene* s;
  try {
    s = &get_scene(scene);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  std::optional<Bvh2> b;
  for (auto _ : state) {
    state.PauseTiming();
    b.reset();
    state.ResumeTiming();
    b.emplace();
    b->build(triangle_bounds(s->mesh));
    benchmark::DoNotOptimize(b->nodes().data());
  }
  const double tris = double(s->triangles());
  const size_t bytes = b->nodes().size() * sizeof(Bvh2Node) + b->prim_indices().size() * 4;
  const size_t mesh_bytes = s->mesh.vertex_count() * 12 + s->mesh.indices.size() * 4;
  state.counters["Mtris"] = benchmark::Counter(tris * double(state.iterations()) * 1e-6, benchmark::Counter::kIsRate);
  state.counters["B/tri"] = double(bytes) / tris;  // nodes + prim_indices (it traverses the mesh itself)
  state.counters["B/tri+mesh"] = double(bytes + mesh_bytes) / tris;
  state.counters["SAH"] = b->sah_cost();
  state.counters["tris"] = tris;
}

void register_scene(const std::string& scene) {
  // One build thread: CPU time of the process (TBB limited to one thread runs everything on the calling thread),
  // which load from other processes disturbs less than wall time. Two threads: wall time (rates follow the same clock).
  for (int threads : {1, 2}) {
    auto* b4 = benchmark::RegisterBenchmark((scene + "/build/wide4/threads:" + std::to_string(threads)).c_str(),
                                            BM_BuildWide<4>, scene, threads);
    auto* b8 = benchmark::RegisterBenchmark((scene + "/build/wide8/threads:" + std::to_string(threads)).c_str(),
                                            BM_BuildWide<8>, scene, threads);
    for (auto* b : {b4, b8}) {
      b->Unit(benchmark::kMillisecond);
      if (threads > 1) b->UseRealTime();
      else b->MeasureProcessCPUTime();
    }
  }
  benchmark::RegisterBenchmark((scene + "/build/bvh2/threads:1").c_str(), BM_BuildBvh2, scene)
      ->Unit(benchmark::kMillisecond)
      ->MeasureProcessCPUTime();
  for (const char* wl : {"primary", "diffuse", "shadow"}) {
    for (Query q : {Query::Closest, Query::Any}) {
      auto reg = [&](Accel a, Mode m) {
        const std::string name = scene + "/" + wl + "/" + name_of(q) + "/" + name_of(a) + "/" + name_of(m);
        // Single-threaded: CPU time of the benchmark thread, which other processes on the machine disturb less
        // than wall time.
        benchmark::RegisterBenchmark(name.c_str(), BM_Trace, scene, std::string(wl), q, a, m)
            ->Unit(benchmark::kMillisecond);
      };
      reg(Accel::Bvh2, Mode::Single);
      for (Accel a : {Accel::Wide4, Accel::Wide8})
        for (Mode m : {Mode::Single, Mode::Packet8, Mode::Packet16}) reg(a, m);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--full") == 0) {
      set_full_run(true);
    } else {
      std::fprintf(stderr, "torte_bench: unknown argument '%s' (Google Benchmark flags, plus --full)\n", argv[i]);
      return 2;
    }
  }
  std::string why;
  if (!shared_data_available(&why)) {
    std::printf("torte_bench: SKIPPED, no benchmark meshes: %s\n", why.c_str());
    return 0;
  }
  benchmark::AddCustomContext("torte_target", traversal_target_name());
  benchmark::AddCustomContext("torte_scenes", [] {
    std::string s;
    for (const std::string& n : scene_names()) s += (s.empty() ? "" : ",") + n;
    return s;
  }());
  benchmark::AddCustomContext("image", std::to_string(image_resolution()) + "x" + std::to_string(image_resolution()));
  for (const std::string& scene : scene_names()) register_scene(scene);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  release_scene();
  return 0;
}
