// embree-compare: identical rays through Embree 3 and torte on the shared workloads (workloads.h), one line per
// workload:
//   workload=<name> tris=<n> threads=<t> torte_mrays=<x> embree_mrays=<y> ratio=<x/y>
//   workload=build tris=<n> threads=<t> torte_mtris=<x> embree_mtris=<y> ratio=<x/y>
// (other lines start with '#'). Like is compared with like:
//   primary         torte packets of 16 (closest)  vs rtcIntersect16
//   primary-single  torte single rays (closest)    vs rtcIntersect1
//   shadow          torte packets of 16 (any hit)  vs rtcOccluded16
//   shadow-single   torte single rays (any hit)    vs rtcOccluded1
//   diffuse         torte single rays (closest)    vs rtcIntersect1
// Embree's packets are timed with both intersect-context flags, COHERENT (which lets rtcIntersect16 /
// rtcOccluded16 trace a packet with its frustum traversal) and INCOHERENT, and the faster one is the
// reference (coherent wins for camera rays, incoherent for the shadow rays, whose origins spread); a '#' line
// gives both. --embree-context coherent|incoherent pins one. Single rays use the default (INCOHERENT) context.
//   build           bounds + SAH build + collapse + leaves  vs rtcCommitScene at RTC_BUILD_QUALITY_MEDIUM
// --mesh FILE.ply|.obj (repeatable; --grow N subdivides it N times like bunny-1m/4m/16m): the same workloads,
// checks and lines on a user's mesh, loaded with torte's readers and framed in the box as the named scenes are
// (workloads.h); the named scenes then run only if --scenes is given too.
// --tree embree: torte's kernels trace Embree's tree instead of torte's (rtcBuildBVH with the settings of Embree's
// triangle builder, copied into torte's layout; embree_tree.h), so a traversal ratio then compares kernels on one
// tree. The build line still compares the two builders.
// Times are medians of --reps repetitions (--stat min: the fastest one), torte and Embree interleaved so that
// load from other processes hits both alike. One thread: traversal is timed in CPU time of the calling thread,
// builds in CPU time of the process (so time the machine's other processes take is not counted; Embree and torte
// are both limited to one thread). With
// --threads T > 1 everything is wall time, rays are split into chunks of 4096 over a TBB arena of T threads
// (torte and Embree alike) and both builders are limited to T threads.
//
// --compact (width 8): the compact layouts (compact_layouts.h: quantised nodes, packed leaves, both) traced
// through the same workloads, timed interleaved with the default layout, one line per layout and workload:
//   layout=<name> workload=<w> tris=<n> threads=<t> default_mrays=<x> layout_mrays=<y> ratio=<y/x>
// with the layouts' bytes per triangle (nodes + leaves + prim_indices) on a '#' line per scene.
//
// Hit distances must agree (relative 1e-4, and hit vs miss); the fraction of disagreeing rays is printed per
// workload and the program fails (exit 1, "FAIL" on stderr) when it exceeds 1e-4 for any workload.
#include <embree3/rtcore.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cctype>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "accel/bvh_build.h"
#include "compact_layouts.h"
#include "embree_rays.h"
#include "embree_tree.h"
#include "core/error.h"
#include "core/parallel.h"
#include "traverse.h"
#include "workloads.h"

using namespace torte;
using namespace torte::bench;

namespace {

constexpr float kRelTol = 1e-4f;
constexpr double kMaxMismatchFraction = 1e-4;
constexpr size_t kChunk = 4096;  // rays per parallel task (a multiple of 64: whole 8x8 tiles)

struct Options {
  int threads = 1;
  int reps = 5;
  int packet = 16;
  int width = kDefaultBvhWidth;
  std::string embree_context = "best";  // Embree's packets: best of both, or "coherent" / "incoherent"
  std::string workloads;                // comma-separated subset of the workloads ("" = all)
  bool min_time = false;                // --stat min: fastest repetition instead of the median
  bool embree_robust = false;           // --embree-robust: RTC_SCENE_FLAG_ROBUST (torte's guarantees)
  bool embree_tree = false;             // --tree embree: torte's kernels on Embree's tree
  bool embree_t_only = false;           // --embree-hits t: Embree's closest hits keep only t (see embree_hit)
  std::vector<std::string> meshes;      // --mesh FILE (repeatable): users' meshes, instead of the named scenes
  int grow = 0;                         // --grow N: subdivide each --mesh N times
  bool scenes_given = false;            // --scenes with --mesh: the named scenes run too, first
  bool compact = false;                 // --compact: the compact layouts next to the default one (width 8)
};
Options g_opt;

// ---- timing ----------------------------------------------------------------------------------------------------

double wall_now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
double cpu_now(clockid_t clock) {
  timespec ts;
  clock_gettime(clock, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
// Builds: with one thread, CPU time of the whole process (whichever threads the builders use, and not the time
// other processes take the core away); with more, wall time.
double build_clock() { return g_opt.threads == 1 ? cpu_now(CLOCK_PROCESS_CPUTIME_ID) : wall_now(); }
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  if (g_opt.min_time) return v.front();
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Runs f(begin, end) over [0, n): directly on this thread with one thread, else in chunks over TBB.
void for_rays(size_t n, const std::function<void(size_t, size_t)>& f) {
  if (g_opt.threads == 1) {
    f(0, n);
    return;
  }
  parallel_for_blocks(size_t(0), (n + kChunk - 1) / kChunk, 1, [&](IndexRange<size_t> r) {
    for (size_t c = r.begin(); c < r.end(); ++c) f(c * kChunk, std::min(n, (c + 1) * kChunk));
  });
}

// Seconds taken by f, in the clock described at the top of the file.
double time_traversal(const std::function<void()>& f) {
  const bool cpu = g_opt.threads == 1;
  const double t0 = cpu ? cpu_now(CLOCK_THREAD_CPUTIME_ID) : wall_now();
  f();
  return (cpu ? cpu_now(CLOCK_THREAD_CPUTIME_ID) : wall_now()) - t0;
}

// ---- comparison ------------------------------------------------------------------------------------------------

bool g_failed = false;

void print_ratio_line(const char* workload, size_t tris, double torte_rate, double embree_rate, bool build) {
  std::printf("workload=%s tris=%zu threads=%d torte_%s=%.3f embree_%s=%.3f ratio=%.3f\n", workload, tris,
              g_opt.threads, build ? "mtris" : "mrays", torte_rate, build ? "mtris" : "mrays", embree_rate,
              torte_rate / embree_rate);
  std::fflush(stdout);
}

void report_check(const char* workload, const Check& vs_embree, const Check& vs_reference, size_t embree_hits) {
  const bool bad = vs_embree.mismatch_fraction() > kMaxMismatchFraction;
  std::printf("# %s: torte vs embree: %zu of %zu rays disagree (%.2e)%s; torte hits %zu, embree hits %zu; "
              "torte vs scalar reference: %zu disagree\n",
              workload, vs_embree.mismatches, vs_embree.rays, vs_embree.mismatch_fraction(),
              bad ? " ABOVE THE 1e-4 LIMIT" : "", vs_embree.hits, embree_hits, vs_reference.mismatches);
  if (bad) {
    std::fprintf(stderr, "embree-compare: FAIL: %s: %.2e of the rays disagree between torte and Embree (limit %.0e)\n",
                 workload, vs_embree.mismatch_fraction(), kMaxMismatchFraction);
    g_failed = true;
  }
}

enum class Kind { Closest, Any };

// --workloads: whether `name` is in the comma-separated list (every workload when there is none).
bool workload_selected(const char* name) {
  if (g_opt.workloads.empty()) return true;
  std::string list = g_opt.workloads, key = name;
  list += ',', key += ',';
  for (size_t at = list.find(key); at != std::string::npos; at = list.find(key, at + 1))
    if (at == 0 || list[at - 1] == ',') return true;
  return false;
}

template <int N>
void compare_workload(const char* name, const BenchScene& s, const Workload& w, const TorteAccel<N>& a,
                      RTCScene scene, Kind kind, bool packets, const CompactAccel* compact) {
  if (!workload_selected(name)) return;
  const size_t n = w.rays.size();
  std::vector<Hit> hits(kind == Kind::Closest ? n : 0), embree_hits_out(kind == Kind::Closest ? n : 0);
  std::vector<uint8_t> torte_occ(kind == Kind::Any ? n : 0), embree_occ(kind == Kind::Any ? n : 0);
  auto run_torte = [&] {
    for_rays(n, [&](size_t b, size_t e) {
      const RaySoA soa = w.rays.soa(b);
      if (kind == Kind::Closest) {
        if (packets) intersect_closest_packets(a.bvh, a.leaves, soa, e - b, hits.data() + b, g_opt.packet);
        else intersect_closest(a.bvh, a.leaves, soa, e - b, hits.data() + b);
      } else {
        if (packets) intersect_any_packets(a.bvh, a.leaves, soa, e - b, torte_occ.data() + b, g_opt.packet);
        else intersect_any(a.bvh, a.leaves, soa, e - b, torte_occ.data() + b);
      }
    });
  };
  auto run_embree = [&](bool coherent) {
    for_rays(n, [&](size_t b, size_t e) {
      if (kind == Kind::Closest) {
        if (packets) embree_closest16(scene, w.rays, b, e, embree_hits_out.data(), coherent, g_opt.embree_t_only);
        else embree_closest1(scene, w.rays, b, e, embree_hits_out.data(), g_opt.embree_t_only);
      } else {
        if (packets) embree_any16(scene, w.rays, b, e, embree_occ.data(), coherent);
        else embree_any1(scene, w.rays, b, e, embree_occ.data());
      }
    });
  };
  // Embree variants timed: [0] COHERENT context, [1] INCOHERENT (single rays: only the default, INCOHERENT).
  const bool try_coherent = packets && g_opt.embree_context != "incoherent";
  const bool try_incoherent = !packets || g_opt.embree_context != "coherent";
  constexpr int kLayouts = int(std::size(kCompactLayouts));
  std::vector<double> tt, te[2], tl[kLayouts];
  std::vector<Hit> layout_hits(compact && kind == Kind::Closest ? n : 0);
  std::vector<uint8_t> layout_occ(compact && kind == Kind::Any ? n : 0);
  Check layout_check[kLayouts];
  auto run_layout = [&](int k) {  // the compact layouts, as run_torte runs the default one
    if constexpr (N == 8)
      for_rays(n, [&](size_t b, size_t e) {
        trace_layout(kCompactLayouts[k], a, *compact, w.rays.soa(b), e - b,
                     kind == Kind::Closest ? layout_hits.data() + b : nullptr,
                     kind == Kind::Any ? layout_occ.data() + b : nullptr, packets ? g_opt.packet : 0);
      });
  };
  for (int r = 0; r < g_opt.reps; ++r) {
    tt.push_back(time_traversal(run_torte));
    if (try_coherent) te[0].push_back(time_traversal([&] { run_embree(true); }));
    if (try_incoherent) te[1].push_back(time_traversal([&] { run_embree(false); }));
    for (int k = 0; compact && k < kLayouts; ++k) {
      tl[k].push_back(time_traversal([&] { run_layout(k); }));
      if (r == 0)
        layout_check[k] = kind == Kind::Closest ? check_closest(w.ref, layout_hits.data(), n, kRelTol)
                                                : check_any(w.ref, layout_occ.data(), n);
    }
  }
  Check vs_embree, vs_ref;
  size_t embree_hits = 0;
  if (kind == Kind::Closest) {
    Reference er;  // Embree's answer as the reference
    er.t.resize(n);
    for (size_t i = 0; i < n; ++i) er.t[i] = embree_hits_out[i].t;
    vs_embree = check_closest(er, hits.data(), n, kRelTol);
    vs_ref = check_closest(w.ref, hits.data(), n, kRelTol);
    for (float t : er.t) embree_hits += t < kInfinity;
    if (!g_opt.embree_t_only) {  // both sides hit: the same triangle? (a shared edge may go either way)
      size_t both = 0, other_prim = 0;
      for (size_t i = 0; i < n; ++i) {
        if (hits[i].prim == kNoHit || embree_hits_out[i].prim == kNoHit) continue;
        // torte's Hit::prim is a leaf-order position; prim_indices maps it to the mesh's triangle, Embree's id.
        ++both, other_prim += a.bvh.prim_indices[hits[i].prim] != embree_hits_out[i].prim;
      }
      std::printf("# %s: of %zu rays both hit, %zu hit another triangle in Embree\n", name, both, other_prim);
    }
  } else {
    Reference er;
    er.occluded = embree_occ;
    vs_embree = check_any(er, torte_occ.data(), n);
    vs_ref = check_any(w.ref, torte_occ.data(), n);
    for (uint8_t o : embree_occ) embree_hits += o;
  }
  const double mt = double(n) / median(tt) * 1e-6;
  const double me_coherent = try_coherent ? double(n) / median(te[0]) * 1e-6 : 0;
  const double me_incoherent = try_incoherent ? double(n) / median(te[1]) * 1e-6 : 0;
  print_ratio_line(name, s.triangles(), mt, std::max(me_coherent, me_incoherent), false);
  if (packets)
    std::printf("# %s: embree_mrays with the COHERENT context %.3f, INCOHERENT %.3f (0: not run)\n", name,
                me_coherent, me_incoherent);
  report_check(name, vs_embree, vs_ref, embree_hits);
  for (int k = 0; compact && k < kLayouts; ++k) {
    const double ml = double(n) / median(tl[k]) * 1e-6;
    std::printf("layout=%s workload=%s tris=%zu threads=%d default_mrays=%.3f layout_mrays=%.3f ratio=%.3f\n",
                layout_name(kCompactLayouts[k]), name, s.triangles(), g_opt.threads, mt, ml, ml / mt);
    std::printf("# %s: %s vs reference: %zu of %zu disagree\n", name, layout_name(kCompactLayouts[k]),
                layout_check[k].mismatches, n);
    if (layout_check[k].mismatch_fraction() > kMaxMismatchFraction) {
      std::fprintf(stderr, "embree-compare: FAIL: %s: layout %s disagrees with the reference on %.2e of the rays\n",
                   name, layout_name(kCompactLayouts[k]), layout_check[k].mismatch_fraction());
      g_failed = true;
    }
  }
}

template <int N>
void run_scene(RTCDevice dev, const BenchScene& s) {
  const TriangleMesh& mesh = s.mesh;
  const size_t tris = s.triangles();
  std::printf("# mesh=%s tris=%zu (model %zu + 12 box) rays: primary %zu, diffuse %zu, shadow %zu\n", s.name.c_str(),
              tris, s.model_triangles, s.primary.rays.size(), s.diffuse.rays.size(), s.shadow.rays.size());
  // Embree's float3 vertex buffer (AoS, + 1 float of padding); made once, outside the timing.
  std::vector<float> vertices(3 * mesh.vertex_count() + 1, 0.0f);
  for (size_t i = 0; i < mesh.vertex_count(); ++i)
    vertices[3 * i] = mesh.x[i], vertices[3 * i + 1] = mesh.y[i], vertices[3 * i + 2] = mesh.z[i];

  // Builds, interleaved. The last ones are kept for tracing.
  std::vector<double> tt, te;
  TorteAccel<N> accel;
  RTCScene scene = nullptr;
  int64_t embree_bytes = 0, embree_peak = 0;
  for (int r = 0; r < g_opt.reps; ++r) {
    accel = {};
    double t0 = build_clock();
    accel = build_torte<N>(mesh);
    tt.push_back(build_clock() - t0);
    if (scene) rtcReleaseScene(scene);
    const int64_t before = g_embree_bytes.load();
    g_embree_peak = before;
    t0 = build_clock();
    scene = build_embree(dev, vertices, mesh, g_opt.embree_robust);
    te.push_back(build_clock() - t0);
    embree_bytes = g_embree_bytes.load() - before;
    embree_peak = g_embree_peak.load() - before;
  }
  print_ratio_line("build", tris, double(tris) / median(tt) * 1e-6, double(tris) / median(te) * 1e-6, true);
  std::printf("# build memory: torte %.1f B/tri (wide%d nodes + prim_indices + leaf triangles; mesh excluded), "
              "embree %.1f B/tri (BVH + leaves, peak during build %.1f B/tri; shared mesh excluded)\n",
              double(accel.bytes()) / double(tris), N, double(embree_bytes) / double(tris),
              double(embree_peak) / double(tris));

  if (g_opt.embree_tree) {
    const BvhStats own = bvh_stats(accel.bvh);
    const BvhBuildOptions block4{.leaf_block_size = 4};  // the metric of bench/RESULTS.md's tree table
    const float own_sah = sah_cost(accel.bvh, block4);
    accel = build_torte_layout_of_embree_tree<N>(dev, mesh);
    const BvhStats e = bvh_stats(accel.bvh);
    std::printf("# --tree embree: torte's kernels trace Embree's tree: %zu nodes, %.2f children/node, %.2f "
                "triangles/leaf, SAH %.3f (torte's own tree: %zu, %.2f, %.2f, SAH %.3f; SAH of wide%d trees, leaf "
                "blocks of 4)\n",
                e.nodes, e.avg_children, e.avg_leaf_size, double(sah_cost(accel.bvh, block4)), own.nodes,
                own.avg_children, own.avg_leaf_size, double(own_sah), N);
  }
  std::unique_ptr<CompactAccel> compact;
  if constexpr (N == 8)
    if (g_opt.compact) {
      compact = std::make_unique<CompactAccel>(build_compact(accel, mesh));
      std::printf("# layouts: bytes/triangle (nodes + leaves + prim_indices; mesh excluded):");
      for (Layout l : kAllLayouts)
        std::printf(" %s %.1f", layout_name(l), layout_bytes_per_triangle(l, accel, *compact, tris));
      std::printf("\n");
    }
  const CompactAccel* c = compact.get();
  compare_workload("primary", s, s.primary, accel, scene, Kind::Closest, true, c);
  compare_workload("primary-single", s, s.primary, accel, scene, Kind::Closest, false, c);
  compare_workload("shadow", s, s.shadow, accel, scene, Kind::Any, true, c);
  compare_workload("shadow-single", s, s.shadow, accel, scene, Kind::Any, false, c);
  compare_workload("diffuse", s, s.diffuse, accel, scene, Kind::Closest, false, c);
  rtcReleaseScene(scene);
}

int usage() {
  std::fprintf(stderr,
               "usage: embree-compare [--help] [--threads T] [--reps R] [--stat median|min] [--workloads a,b,...] "
               "[--full] "
               "[--scenes a,b,...] [--mesh FILE.ply|.obj ...] [--grow N] [--packet 8|16] "
               "[--width 4|8] [--embree-context best|coherent|incoherent] [--embree-robust] [--embree-hits full|t] "
               "[--tree torte|embree] [--compact]\n"
               "  --threads T  traversal and build threads (default 1)\n"
               "  --reps R     repetitions per measurement; medians are printed (default 5)\n"
               "  --stat min   print the fastest repetition instead of the median (A/B runs on a loaded machine)\n"
               "  --workloads  subset of primary,primary-single,shadow,shadow-single,diffuse (builds always run)\n"
               "  --full       add the 4 M and 16 M triangle bunnies (or TORTE_BENCH_FULL=1)\n"
               "  --scenes     subset of bunny,dragon,bunny-1m,bunny-4m,bunny-16m (or TORTE_BENCH_SCENES)\n"
               "  --mesh FILE  run on this .ply or .obj mesh instead (repeatable; torte's readers), framed in the\n"
               "               closed box like the named scenes; with --scenes the named ones run too, first\n"
               "  --grow N     subdivide each --mesh N times (x4 triangles each, as bunny-1m is the bunny grown 2)\n"
               "  --packet     torte's packet size against rtcIntersect16 / rtcOccluded16 (default 16)\n"
               "  --width      torte's BVH width (default %d)\n"
               "  --embree-context  Embree's packets: the faster of the COHERENT and INCOHERENT intersect\n"
               "               contexts (best, default), or only one of them\n"
               "  --embree-robust  build Embree's scene with RTC_SCENE_FLAG_ROBUST: conservative box tests and\n"
               "               a watertight triangle test, the guarantees torte always gives (default: Embree's\n"
               "               faster default mode, the reference of the targets)\n"
               "  --embree-hits t  Embree's closest hits keep only t instead of the 20-byte Hit record torte\n"
               "               writes (t, primitive, barycentrics, instance; default full: the same output)\n"
               "  --tree embree  torte's kernels trace a tree from Embree's SAH builder (rtcBuildBVH with its\n"
               "               triangle builder's settings) in torte's layout: kernels compared on one tree\n"
               "  --compact    also trace the compact layouts, interleaved: speed ratios, bytes per triangle\n",
               kDefaultBvhWidth);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    if (a == "--help" || a == "-h") {
      usage();
      return 0;
    } else if (a == "--full") {
      set_full_run(true);
    } else if (a == "--embree-robust") {
      g_opt.embree_robust = true;
    } else if (a == "--compact") {
      g_opt.compact = true;
    } else if (a == "--embree-hits") {
      const char* v = value();
      if (!v || (std::string(v) != "full" && std::string(v) != "t")) return usage();
      g_opt.embree_t_only = std::string(v) == "t";
    } else if (a == "--stat" || a == "--workloads") {
      const char* v = value();
      if (!v) return usage();
      if (a == "--workloads") g_opt.workloads = v;
      else if (std::string(v) == "min") g_opt.min_time = true;
      else if (std::string(v) != "median") return usage();
    } else if (a == "--embree-context") {
      const char* v = value();
      if (!v) return usage();
      g_opt.embree_context = v;
    } else if (a == "--tree") {
      const char* v = value();
      if (!v || (std::string(v) != "torte" && std::string(v) != "embree")) return usage();
      g_opt.embree_tree = std::string(v) == "embree";
    } else if (a == "--mesh") {
      const char* v = value();
      if (!v) return usage();
      g_opt.meshes.push_back(v);
    } else if (a == "--grow") {
      const char* v = value();
      char* end = nullptr;
      const long n = v ? std::strtol(v, &end, 10) : -1;
      if (!v || *end || n < 0 || n > 8) return usage();
      g_opt.grow = int(n);
    } else if (a == "--threads" || a == "--reps" || a == "--packet" || a == "--width" || a == "--scenes") {
      const char* v = value();
      if (!v) return usage();
      if (a == "--scenes") setenv("TORTE_BENCH_SCENES", v, 1), g_opt.scenes_given = true;
      else (a == "--threads" ? g_opt.threads : a == "--reps" ? g_opt.reps : a == "--packet" ? g_opt.packet
                                                                                          : g_opt.width) = std::atoi(v);
    } else {
      return usage();
    }
  }
  if (g_opt.threads < 1 || g_opt.reps < 1 || (g_opt.packet != 8 && g_opt.packet != 16) ||
      (g_opt.width != 4 && g_opt.width != 8) || (g_opt.compact && g_opt.width != 8) ||
      (g_opt.embree_context != "best" && g_opt.embree_context != "coherent" && g_opt.embree_context != "incoherent"))
    return usage();

  // A user's mesh must be there before anything runs: a one-line error otherwise (its content is checked as it
  // loads, also a one-line error).
  for (const std::string& path : g_opt.meshes) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec) || !std::ifstream(path, std::ios::binary)) {
      std::fprintf(stderr, "embree-compare: cannot read mesh %s: %s\n", path.c_str(),
                   std::filesystem::exists(path, ec) ? "not a readable file" : "no such file");
      return 1;
    }
    if (ext != ".ply" && ext != ".obj") {
      std::fprintf(stderr, "embree-compare: mesh %s: expected a .ply or .obj file\n", path.c_str());
      return 1;
    }
  }
  if (g_opt.grow > 0 && g_opt.meshes.empty()) return usage();
  const bool named_scenes = g_opt.meshes.empty() || g_opt.scenes_given;
  std::string why;
  if (named_scenes && !shared_data_available(&why)) {
    std::printf("embree-compare: SKIPPED, no benchmark meshes: %s\n", why.c_str());
    return 0;
  }
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(g_opt.threads));
  const std::string config = "threads=" + std::to_string(g_opt.threads);
  RTCDevice dev = rtcNewDevice(config.c_str());
  if (!dev) {
    std::fprintf(stderr, "embree-compare: rtcNewDevice failed (error %d)\n", int(rtcGetDeviceError(nullptr)));
    return 3;
  }
  rtcSetDeviceErrorFunction(dev, embree_error, nullptr);
  rtcSetDeviceMemoryMonitorFunction(dev, embree_memory_monitor, nullptr);
  std::printf("# embree-compare: Embree %s, torte traversal target %s, torte wide%d, torte packet %d, Embree packet "
              "context %s, Embree mode %s, Embree closest hits kept: %s, torte traces %s tree, threads %d, %s of %d, "
              "%s\n",
              RTC_VERSION_STRING, traversal_target_name(), g_opt.width, g_opt.packet,
              g_opt.embree_context.c_str(), g_opt.embree_robust ? "robust" : "default",
              g_opt.embree_t_only ? "t only" : "full Hit record, as torte",
              g_opt.embree_tree ? "Embree's" : "its own", g_opt.threads,
              g_opt.min_time ? "minimum" : "median", g_opt.reps,
              g_opt.threads == 1 ? "traversal in thread CPU time, builds in process CPU time" : "wall time");
  std::fflush(stdout);
  try {
    auto run = [&](const BenchScene& s) {
      if (g_opt.width == 4) run_scene<4>(dev, s);
      else run_scene<8>(dev, s);
      release_scene();
    };
    if (named_scenes)
      for (const std::string& name : scene_names()) run(get_scene(name));
    for (const std::string& path : g_opt.meshes) run(get_mesh_scene(path, g_opt.grow));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "embree-compare: %s\n", e.what());
    rtcReleaseDevice(dev);
    return 1;
  }
  rtcReleaseDevice(dev);
  if (g_failed) {
    std::fprintf(stderr, "embree-compare: FAIL: torte and Embree disagree on more than 1e-4 of the rays (see above)\n");
    return 1;
  }
  return 0;
}
