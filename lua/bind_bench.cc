// torte.bench{...}: times one traversal kernel on one kind of ray through any scene a script builds (meshes,
// quadrics, voxel grids, instances), on a chosen SIMD target, and validates every result against the scalar
// reference (the single-ray kernel on Highway's scalar target), so that a wrong kernel cannot look fast.
//
// Rays, all deterministic for a seed:
//   camera:  one ray per pixel centre, ordered so that 16 consecutive rays are a 4x4 pixel block and 8 a 4x2
//            half of it (the groups the packet kernels take), tile by 8x8 tile;
//   diffuse: one cosine-distributed ray per camera hit around its geometric normal (turned towards the camera);
//   shadow:  one ray per camera hit towards a point sampled on one of the scene's lights (chosen by hash).
// Camera and diffuse rays also report their mean nodes visited and primitives tested (Scene::intersect's counts).
// Google Benchmark is what bench/ uses for fixed workloads; it cannot be driven from a script on the script's
// own scene, so the repetitions and their statistics are timed here.
//
// kernel = "embree" (builds with Embree 3, TORTE_HAVE_EMBREE; see embree_* below): the same rays through Embree,
// on an Embree scene of the torte scene's world-space triangles, validated against the same reference.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#ifdef TORTE_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

#include "binding.h"
#include "camera/camera.h"
#include "core/memory_budget.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "light/light.h"
#include "simd/simd_target.h"
#include "types.h"

namespace torte::lua {

namespace {

enum class RayKind { kCamera, kDiffuse, kShadow };

RayArrays camera_rays(const Camera& camera, int width, int height) {
  RayArrays rays;
  for (int ty = 0; ty < height; ty += 8)
    for (int tx = 0; tx < width; tx += 8)
      for (int block = 0; block < 4; ++block)
        for (int half = 0; half < 2; ++half)
          for (int row = 0; row < 2; ++row)
            for (int col = 0; col < 4; ++col) {
              const int x = tx + (block % 2) * 4 + col, y = ty + (block / 2) * 4 + half * 2 + row;
              if (x >= width || y >= height) continue;
              const Ray r = camera.generate_ray(Vec2f(float(x) + 0.5f, float(y) + 0.5f));
              rays.push(r);
            }
  return rays;
}

// Two uniform numbers for ray i of stream `stream`, the same on every run and thread count.
Vec2f hashed_2d(uint64_t seed, uint64_t stream, size_t i) {
  Pcg32 rng(mix_bits(seed * 0x9e3779b97f4a7c15ull + i), stream);
  const float u = rng.next_float();
  return {u, rng.next_float()};
}

RayArrays secondary_rays(const Scene& scene, const RayArrays& primary, const std::vector<Hit>& hits, RayKind kind,
                         uint64_t seed) {
  RayArrays rays;
  for (size_t i = 0; i < primary.size(); ++i) {
    if (hits[i].prim == kNoHit) continue;
    const Ray pr = ray_at(primary.soa(), i);
    const SurfaceHit s = scene.surface(pr, hits[i]);
    if (kind == RayKind::kDiffuse) {
      const Vec3f n = dot(s.ng, pr.d) > 0 ? -s.ng : s.ng;
      const Vec3f d = Frame::from_z(n).to_world(sample_cosine_hemisphere(hashed_2d(seed, 1, i)));
      rays.push({offset_origin(s.p, s.ng, d), d, kInfinity});
    } else {
      const Light& light = scene.lights[Pcg32(mix_bits(seed + i), 3).next_u32() % scene.lights.size()];
      LightSample ls;
      if (!sample_light(scene, light, s.p, hashed_2d(seed, 2, i), &ls)) continue;
      const Vec3f o = offset_origin(s.p, s.ng, ls.wi);
      const float t = ls.distance == kInfinity ? kInfinity : length(s.p + ls.wi * ls.distance - o) * (1 - 1e-4f);
      rays.push({o, ls.wi, t});
    }
  }
  return rays;
}

// Runs body(first, count) over rays [0, n) in chunks of 4096 (aligned to 16 rays) on `threads` threads.
void for_chunks(size_t n, int threads, const std::function<void(size_t, size_t)>& body) {
  constexpr size_t chunk = 4096;
  if (threads == 1) {
    for (size_t first = 0; first < n; first += chunk) body(first, std::min(chunk, n - first));
    return;
  }
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(size_t(0), (n + chunk - 1) / chunk,
                      [&](size_t c) { body(c * chunk, std::min(chunk, n - c * chunk)); });
  });
}

// Traces all rays with `kernel` on `threads` threads.
void trace(const Scene& scene, const RayArrays& rays, RayKind kind, TraceKernel kernel, int threads,
           std::vector<Hit>* hits, std::vector<uint8_t>* blocked) {
  for_chunks(rays.size(), threads, [&](size_t first, size_t count) {
    if (kind == RayKind::kShadow) scene.accel().occluded(rays.soa(first), count, blocked->data() + first, kernel);
    else scene.accel().intersect(rays.soa(first), count, hits->data() + first, kernel);
  });
}

// ---- kernel = "embree" -----------------------------------------------------------------------------------------
//
// The Embree scene: one RTC_GEOMETRY_TYPE_TRIANGLE geometry holding the root geometry set's triangles in world
// space, in torte's own (leaf-order) numbering, so Embree's primID is torte's Hit::prim. The scene's meshes have
// released their positions once built (scene/scene.h), so each triangle's vertices are read back through the
// set's surface() at barycentrics (0,0), (1,0), (0,1), which reproduces the leaf vertices exactly; the result is a
// triangle soup (36 + 12 bytes per triangle, shared with Embree) built at RTC_BUILD_QUALITY_MEDIUM in Embree's
// default (non-robust) mode, as embree-compare builds its scenes.
//
// Built once per torte scene and kept for the next calls on it: one Embree scene for the whole process, keyed by
// the torte scene it was made from (a weak pointer, and the builder's fingerprint, which lets it be freed before
// a changed scene is flattened). The cost, on the first embree call for a scene only: the read-back and Embree's
// build (all cores), about 0.7 s per million triangles here (the bunny grown to 1.1 M: 0.76 s on 2 loaded cores),
// plus the 48 B/tri soup and Embree's BVH while it is kept; it lingers after the torte scene is gone until the
// next embree call (or the process ends).
//
// The Embree call per ray kind is the one bench/embree_compare.cc sets against torte's kernels (its comparable
// path), with the intersect context its "best" choice picks for those rays:
//   camera  rtcIntersect16 on each 4x4 block of 16 rays, COHERENT context  (embree-compare "primary")
//   shadow  rtcOccluded16 on each group of 16, INCOHERENT context          (embree-compare "shadow")
//   diffuse rtcIntersect1, one ray at a time                                (embree-compare "diffuse")
#ifdef TORTE_HAVE_EMBREE
struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::weak_ptr<const Scene> of;     // the torte scene it was built from
  std::vector<uint64_t> fingerprint;  // and that scene's builder fingerprint
  std::vector<float> vertices;        // 9 floats per triangle, + 1 of padding (Embree's 16-byte loads)
  std::vector<uint32_t> indices;      // 0, 1, 2, ...
  std::string error;                  // the device's last error message

  void release() {
    if (scene) rtcReleaseScene(scene);
    scene = nullptr;
    of.reset();
    fingerprint.clear();
    std::vector<float>().swap(vertices);
    std::vector<uint32_t>().swap(indices);
  }
};

std::mutex g_embree_mutex;
// Never destroyed: Embree's device is released by the process's end, not by a static destructor racing TBB's.
EmbreeScene& embree_cache() {
  static EmbreeScene* cache = new EmbreeScene;
  return *cache;
}

void embree_check(EmbreeScene& e, const char* what) {
  const RTCError code = rtcGetDeviceError(e.device);
  if (code != RTC_ERROR_NONE)
    throw Error(std::string("torte.bench: Embree ") + what + " failed (error " + std::to_string(int(code)) + ": " +
                e.error + ")");
}

// "1 quadric, 2 instances", or "" for a scene of triangle meshes only.
std::string non_triangle_parts(const Scene& scene) {
  std::string out;
  auto add = [&](size_t n, const char* one, const char* many) {
    if (n == 0) return;
    out += (out.empty() ? "" : ", ") + std::to_string(n) + " " + (n == 1 ? one : many);
  };
  add(scene.quadrics.size(), "quadric", "quadrics");
  add(scene.grids.size(), "voxel grid", "voxel grids");
  add(scene.instances.size(), "instance", "instances");
  return out;
}

// The Embree scene of `scene`, built unless the cache holds it (*reused says which). Call under g_embree_mutex.
const EmbreeScene& embree_scene(const std::shared_ptr<const Scene>& scene, const std::vector<uint64_t>& fingerprint,
                                bool* reused) {
  EmbreeScene& e = embree_cache();
  *reused = e.scene && e.of.lock() == scene;
  if (*reused) return e;
  e.release();
  if (!e.device) {
    e.device = rtcNewDevice(nullptr);
    if (!e.device)
      throw Error("torte.bench: Embree's rtcNewDevice failed (error " +
                  std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    auto on_error = [](void* user, RTCError, const char* str) {
      static_cast<EmbreeScene*>(user)->error = str ? str : "";
    };
    rtcSetDeviceErrorFunction(e.device, on_error, &e);
  }
  const GeometrySet& root = scene->accel().root();
  const size_t n = root.triangle_count();
  e.vertices.assign(9 * n + 1, 0.0f);
  e.indices.resize(3 * n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t t = r.begin(); t < r.end(); ++t) {
      for (int k = 0; k < 3; ++k) {
        Hit h;
        h.t = 1, h.prim = uint32_t(t), h.b1 = k == 1 ? 1.0f : 0.0f, h.b2 = k == 2 ? 1.0f : 0.0f;
        const Vec3f p = root.surface(h).p;  // p0 * 1 + p1 * 0 + p2 * 0: the vertex itself
        float* v = &e.vertices[9 * t + 3 * size_t(k)];
        v[0] = p.x, v[1] = p.y, v[2] = p.z;
        e.indices[3 * t + size_t(k)] = uint32_t(3 * t + size_t(k));
      }
    }
  });
  e.error.clear();
  e.scene = rtcNewScene(e.device);
  rtcSetSceneBuildQuality(e.scene, RTC_BUILD_QUALITY_MEDIUM);
  if (n > 0) {
    RTCGeometry g = rtcNewGeometry(e.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_MEDIUM);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, e.vertices.data(), 0,
                               3 * sizeof(float), 3 * n);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, e.indices.data(), 0,
                               3 * sizeof(uint32_t), n);
    rtcCommitGeometry(g);
    rtcAttachGeometry(e.scene, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(e.scene);
  try {
    embree_check(e, "scene build");
  } catch (...) {
    e.release();
    throw;
  }
  e.of = scene;
  e.fingerprint = fingerprint;
  return e;
}

Hit embree_hit(bool hit, float t, uint32_t prim, float u, float v) {
  return hit ? Hit{t, prim, u, v, kNoHit} : Hit{};
}

// Rays [first, first + count) through Embree, with the call of the table above for `kind`.
void embree_trace_chunk(RTCScene scene, const RayArrays& rays, RayKind kind, size_t first, size_t count, Hit* hits,
                        uint8_t* blocked) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  const size_t end = first + count;
  if (kind == RayKind::kDiffuse) {
    for (size_t i = first; i < end; ++i) {
      RTCRayHit rh;
      rh.ray.org_x = rays.ox[i], rh.ray.org_y = rays.oy[i], rh.ray.org_z = rays.oz[i], rh.ray.tnear = 0;
      rh.ray.dir_x = rays.dx[i], rh.ray.dir_y = rays.dy[i], rh.ray.dir_z = rays.dz[i], rh.ray.time = 0;
      rh.ray.tfar = rays.t_max[i], rh.ray.mask = ~0u, rh.ray.id = uint32_t(i), rh.ray.flags = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &ctx, &rh);
      hits[i] = embree_hit(rh.hit.geomID != RTC_INVALID_GEOMETRY_ID, rh.ray.tfar, rh.hit.primID, rh.hit.u, rh.hit.v);
    }
    return;
  }
  ctx.flags = kind == RayKind::kCamera ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[16];
  auto load = [&](RTCRay16& r, size_t i) {  // rays [i, i + 16), those past the end invalid
    for (int k = 0; k < 16; ++k) {
      const size_t j = std::min(i + size_t(k), end - 1);
      valid[k] = i + size_t(k) < end ? -1 : 0;
      r.org_x[k] = rays.ox[j], r.org_y[k] = rays.oy[j], r.org_z[k] = rays.oz[j], r.tnear[k] = 0;
      r.dir_x[k] = rays.dx[j], r.dir_y[k] = rays.dy[j], r.dir_z[k] = rays.dz[j], r.time[k] = 0;
      r.tfar[k] = rays.t_max[j], r.mask[k] = ~0u, r.id[k] = uint32_t(j), r.flags[k] = 0;
    }
  };
  for (size_t i = first; i < end; i += 16) {
    load(rh.ray, i);
    const int lanes = int(std::min<size_t>(16, end - i));
    if (kind == RayKind::kShadow) {
      rtcOccluded16(valid, scene, &ctx, &rh.ray);
      for (int k = 0; k < lanes; ++k) blocked[i + size_t(k)] = rh.ray.tfar[k] < 0;  // Embree: tfar = -inf if blocked
    } else {
      for (int k = 0; k < 16; ++k)
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect16(valid, scene, &ctx, &rh);
      for (int k = 0; k < lanes; ++k)
        hits[i + size_t(k)] = embree_hit(rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID, rh.ray.tfar[k],
                                         rh.hit.primID[k], rh.hit.u[k], rh.hit.v[k]);
    }
  }
}

void trace_embree(const EmbreeScene& e, const RayArrays& rays, RayKind kind, int threads, std::vector<Hit>* hits,
                  std::vector<uint8_t>* blocked) {
  for_chunks(rays.size(), threads, [&](size_t first, size_t count) {
    embree_trace_chunk(e.scene, rays, kind, first, count, hits->data(), blocked->data());
  });
}
#endif  // TORTE_HAVE_EMBREE

// Restores the SIMD target a script had when torte.bench returns or fails.
struct TargetGuard {
  std::string saved = simd::requested_target();
  ~TargetGuard() {
    try {
      simd::use_target(saved);
    } catch (...) {  // it was in use a moment ago
    }
  }
};

int l_bench(lua_State* L) {
  KwArgs kw(L, 1, "torte.bench");
  auto builder = kw.object<SceneBuilder>("scene");
  auto camera_desc = kw.object<CameraDesc>("camera");
  const std::string rays_name = kw.string("rays", "camera");
  const std::string kernel_name = kw.string("kernel", "packet8");
  const int width = kw.integer("width", 512), height = kw.integer("height", 512);
  const int reps = kw.integer("reps", 5);
  const int threads = kw.integer("threads", 1);
  const int seed = kw.integer("seed", 0);
  const std::string target = kw.string("simd", simd::requested_target());
  kw.finish();
  RayKind kind = RayKind::kCamera;
  if (rays_name == "diffuse") kind = RayKind::kDiffuse;
  else if (rays_name == "shadow") kind = RayKind::kShadow;
  else if (rays_name != "camera") kw.fail("rays", "must be \"camera\", \"diffuse\" or \"shadow\", got \"" + rays_name + "\"");
  TraceKernel kernel = TraceKernel::kPacket8;
  const bool embree = kernel_name == "embree";
  if (kernel_name == "single") kernel = TraceKernel::kSingle;
  else if (kernel_name == "packet16") kernel = TraceKernel::kPacket16;
  else if (kernel_name != "packet8" && !embree)
    kw.fail("kernel", "must be \"single\", \"packet8\" or \"packet16\" (or \"embree\", the same rays through "
                      "Embree), got \"" + kernel_name + "\"");
#ifndef TORTE_HAVE_EMBREE
  if (embree)
    throw Error("torte.bench: kernel \"embree\" is not available: torte was built without Embree (install "
                "libembree-dev, scripts/install-deps.sh --bench, and reconfigure)");
#endif
  if (width < 1 || width > 16384 || height < 1 || height > 16384) kw.fail("width", "and height must be in 1..16384");
  if (reps < 1 || reps > 10000) kw.fail("reps", "must be in 1..10000");
  const int max_threads = int(std::max(1u, std::thread::hardware_concurrency()));
  if (threads < 1 || threads > max_threads) kw.fail("threads", "must be in 1.." + std::to_string(max_threads));
  if (seed < 0) kw.fail("seed", "must be a non-negative integer");

#ifdef TORTE_HAVE_EMBREE
  std::unique_lock<std::mutex> embree_lock(g_embree_mutex, std::defer_lock);
  std::vector<uint64_t> fingerprint;
  if (embree) {
    embree_lock.lock();
    fingerprint = builder->fingerprint();
    // A changed scene: free its Embree scene before the new one is flattened (never two large scenes at once).
    if (embree_cache().fingerprint != fingerprint) embree_cache().release();
  }
#endif
  const SceneCache::Lookup built = cached_scene(L, *builder, "torte.bench");
  const Scene& scene = *built.scene;
  if (kind == RayKind::kShadow && scene.lights.empty()) kw.fail("rays", "\"shadow\" needs a scene with lights");
  bool embree_reused = true;
#ifdef TORTE_HAVE_EMBREE
  const EmbreeScene* embree_scene_built = nullptr;
  if (embree) {
    if (const std::string parts = non_triangle_parts(scene); !parts.empty())
      throw Error("torte.bench: kernel \"embree\" supports scenes of triangle meshes only (this scene has " + parts +
                  ")");
    embree_scene_built = &embree_scene(built.scene, fingerprint, &embree_reused);
  }
#endif
  const Camera camera(*camera_desc, width, height);
  // Per ray: its seven floats (twice while the arrays grow), the reference's and the timed hits, occlusion flags.
  reserve_memory(uint64_t(width) * uint64_t(height) * (2 * 7 * sizeof(float) + 2 * sizeof(Hit) + 2),
                 "torte.bench: the rays of a " + std::to_string(width) + "x" + std::to_string(height) + " camera");

  TargetGuard guard;
  // The reference: every ray through the single-ray kernel on the lowest target compiled in ("scalar", Highway's
  // EMU128, in every build but those that compile one target only, such as the sanitizer builds).
  std::string reference_target;
  for (const simd::TargetInfo& t : simd::compiled_targets())
    if (t.supported) reference_target = t.name;
  simd::use_target(reference_target);
  RayArrays rays = camera_rays(camera, width, height);
  std::vector<Hit> ref_hits(rays.size()), hits;
  std::vector<uint8_t> ref_blocked, blocked;
  trace(scene, rays, RayKind::kCamera, TraceKernel::kSingle, 1, &ref_hits, nullptr);
  if (kind != RayKind::kCamera) {
    rays = secondary_rays(scene, rays, ref_hits, kind, uint64_t(seed));
    ref_hits.assign(rays.size(), Hit{});
    ref_blocked.assign(rays.size(), 0);
    trace(scene, rays, kind, TraceKernel::kSingle, 1, &ref_hits, &ref_blocked);
  }
  // The work per closest-hit ray on the reference target (the traversal_cost AOV's counts): the tree's quality
  // beside its speed. Shadow rays take any-hit kernels, which have no counting variant.
  uint64_t nodes = 0, prims = 0;
  if (kind != RayKind::kShadow) {
    std::vector<TraversalCost> costs(rays.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i < r.end(); ++i) {
        Ray ray = rays.ray(i);
        Hit hit;
        scene.intersect(ray, &hit, &costs[i]);
      }
    });
    for (const TraversalCost& c : costs) nodes += c.nodes, prims += c.prims;
  }
  simd::use_target(target);  // an unknown or unsupported target fails here, naming the choices
  const std::string used_target = simd::current_target();
  hits.assign(rays.size(), Hit{});
  blocked.assign(rays.size(), 0);
  std::vector<double> seconds;
  for (int r = 0; r < reps; ++r) {
    if (interrupt_requested()) throw Interrupted("interrupted: torte.bench stopped");
    const auto t0 = std::chrono::steady_clock::now();
#ifdef TORTE_HAVE_EMBREE
    if (embree) trace_embree(*embree_scene_built, rays, kind, threads, &hits, &blocked);
    else
#endif
      trace(scene, rays, kind, kernel, threads, &hits, &blocked);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }

  // Validation: the same hit or miss (occlusion) as the reference, and the same distance to 1e-4 relative.
  size_t found = 0, ref_found = 0, mismatches = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    if (kind == RayKind::kShadow) {
      found += blocked[i] != 0, ref_found += ref_blocked[i] != 0;
      mismatches += (blocked[i] != 0) != (ref_blocked[i] != 0);
    } else {
      const bool hit = hits[i].prim != kNoHit, ref_hit = ref_hits[i].prim != kNoHit;
      found += hit, ref_found += ref_hit;
      mismatches += hit != ref_hit ||
                    (hit && std::fabs(hits[i].t - ref_hits[i].t) > 1e-4f * std::max(1.0f, ref_hits[i].t));
    }
  }
  std::vector<double> sorted = seconds;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2], n = double(rays.size());
  lua_newtable(L);
  auto set_number = [&](const char* key, double v) {
    lua_pushnumber(L, v);
    lua_setfield(L, -2, key);
  };
  auto set_string = [&](const char* key, const std::string& v) {
    lua_pushstring(L, v.c_str());
    lua_setfield(L, -2, key);
  };
  set_number("mrays", n / median * 1e-6);
  set_number("mrays_min", n / sorted.back() * 1e-6);
  set_number("mrays_max", n / sorted.front() * 1e-6);
  set_number("seconds", median);
  auto set_integer = [&](const char* key, size_t v) {
    lua_pushinteger(L, lua_Integer(v));
    lua_setfield(L, -2, key);
  };
  set_integer("rays", rays.size());
  set_integer("hits", found);
  set_integer("reference_hits", ref_found);
  set_integer("mismatches", mismatches);
  if (kind != RayKind::kShadow && n > 0) {
    set_number("nodes_per_ray", double(nodes) / n);
    set_number("prims_per_ray", double(prims) / n);
  }
  // Kernels on other targets may part on a ray grazing an edge (different rounding); more than 1 in 10^4 is a bug.
  lua_pushboolean(L, double(mismatches) <= 1e-4 * n);
  lua_setfield(L, -2, "valid");
  set_string("kernel", kernel_name);
  set_string("rays_kind", rays_name);
  set_string("simd", used_target);
  set_string("reference_simd", reference_target);
  set_integer("threads", size_t(threads));
  lua_pushboolean(L, built.reused && embree_reused);  // kernel = "embree": and its Embree scene
  lua_setfield(L, -2, "scene_reused");
  return 1;
}

}  // namespace

void open_bench(lua_State* L, int torte_index) {
  lua_pushcfunction(L, guarded<l_bench>);
  lua_setfield(L, torte_index, "bench");
}

}  // namespace torte::lua
