// torte.bench{...}: times one traversal kernel on one kind of ray through any scene a script builds (meshes,
// quadrics, voxel grids, instances), on a chosen SIMD target, and validates every result against the scalar
// reference (the single-ray kernel on Highway's scalar target), so that a wrong kernel cannot look fast.
//
// Rays, all deterministic for a seed:
//   camera:  one ray per pixel centre, ordered so that 16 consecutive rays are a 4x4 pixel block and 8 a 4x2
//            half of it (the groups the packet kernels take), tile by 8x8 tile;
//   diffuse: one cosine-distributed ray per camera hit around its geometric normal (turned towards the camera);
//   shadow:  one ray per camera hit towards a point sampled on one of the scene's lights (chosen by hash).
// Google Benchmark is what bench/ uses for fixed workloads; it cannot be driven from a script on the script's
// own scene, so the repetitions and their statistics are timed here.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "binding.h"
#include "camera/camera.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "light/light.h"
#include "simd/simd_target.h"
#include "types.h"

namespace torte::lua {

namespace {

enum class RayKind { kCamera, kDiffuse, kShadow };

struct RayArrays {
  std::vector<float> ox, oy, oz, dx, dy, dz, t_max;
  size_t size() const { return ox.size(); }
  void push(Vec3f o, Vec3f d, float t) {
    ox.push_back(o.x), oy.push_back(o.y), oz.push_back(o.z);
    dx.push_back(d.x), dy.push_back(d.y), dz.push_back(d.z);
    t_max.push_back(t);
  }
  RaySoA soa(size_t offset = 0) const {
    return {ox.data() + offset, oy.data() + offset, oz.data() + offset, dx.data() + offset,
            dy.data() + offset, dz.data() + offset, t_max.data() + offset};
  }
};

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
              rays.push(r.o, r.d, r.t_max);
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
      rays.push(offset_origin(s.p, s.ng, d), d, kInfinity);
    } else {
      const Light& light = scene.lights[Pcg32(mix_bits(seed + i), 3).next_u32() % scene.lights.size()];
      LightSample ls;
      if (!sample_light(scene, light, s.p, hashed_2d(seed, 2, i), &ls)) continue;
      const Vec3f o = offset_origin(s.p, s.ng, ls.wi);
      const float t = ls.distance == kInfinity ? kInfinity : length(s.p + ls.wi * ls.distance - o) * (1 - 1e-4f);
      rays.push(o, ls.wi, t);
    }
  }
  return rays;
}

// Traces all rays with `kernel` on `threads` threads, in chunks aligned to 16 rays.
void trace(const Scene& scene, const RayArrays& rays, RayKind kind, TraceKernel kernel, int threads,
           std::vector<Hit>* hits, std::vector<uint8_t>* blocked) {
  const size_t n = rays.size(), chunk = 4096;
  auto body = [&](size_t first) {
    const size_t count = std::min(chunk, n - first);
    if (kind == RayKind::kShadow) scene.accel().occluded(rays.soa(first), count, blocked->data() + first, kernel);
    else scene.accel().intersect(rays.soa(first), count, hits->data() + first, kernel);
  };
  if (threads == 1) {
    for (size_t first = 0; first < n; first += chunk) body(first);
    return;
  }
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(size_t(0), (n + chunk - 1) / chunk, [&](size_t c) { body(c * chunk); });
  });
}

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
  if (kernel_name == "single") kernel = TraceKernel::kSingle;
  else if (kernel_name == "packet16") kernel = TraceKernel::kPacket16;
  else if (kernel_name != "packet8")
    kw.fail("kernel", "must be \"single\", \"packet8\" or \"packet16\", got \"" + kernel_name + "\"");
  if (width < 1 || width > 16384 || height < 1 || height > 16384) kw.fail("width", "and height must be in 1..16384");
  if (reps < 1 || reps > 10000) kw.fail("reps", "must be in 1..10000");
  const int max_threads = int(std::max(1u, std::thread::hardware_concurrency()));
  if (threads < 1 || threads > max_threads) kw.fail("threads", "must be in 1.." + std::to_string(max_threads));
  if (seed < 0) kw.fail("seed", "must be a non-negative integer");

  const SceneCache::Lookup built = cached_scene(L, *builder, "torte.bench");
  const Scene& scene = *built.scene;
  if (kind == RayKind::kShadow && scene.lights.empty()) kw.fail("rays", "\"shadow\" needs a scene with lights");
  const Camera camera(*camera_desc, width, height);

  TargetGuard guard;
  // The reference: every ray on the scalar target through the single-ray kernel.
  simd::use_target("scalar");
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
  simd::use_target(target);  // an unknown or unsupported target fails here, naming the choices
  const std::string used_target = simd::current_target();
  hits.assign(rays.size(), Hit{});
  blocked.assign(rays.size(), 0);
  std::vector<double> seconds;
  for (int r = 0; r < reps; ++r) {
    if (interrupt_requested()) throw Interrupted("interrupted: torte.bench stopped");
    const auto t0 = std::chrono::steady_clock::now();
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
  // Kernels on other targets may part on a ray grazing an edge (different rounding); more than 1 in 10^4 is a bug.
  lua_pushboolean(L, double(mismatches) <= 1e-4 * n);
  lua_setfield(L, -2, "valid");
  set_string("kernel", kernel_name);
  set_string("rays_kind", rays_name);
  set_string("simd", used_target);
  set_integer("threads", size_t(threads));
  lua_pushboolean(L, built.reused);
  lua_setfield(L, -2, "scene_reused");
  return 1;
}

}  // namespace

void open_bench(lua_State* L, int torte_index) {
  lua_pushcfunction(L, guarded<l_bench>);
  lua_setfield(L, torte_index, "bench");
}

}  // namespace torte::lua
