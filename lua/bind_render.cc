// torte.scene() and its methods, torte.render{...} and torte.filter.* (the image render returns: bind_image.cc).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <unordered_set>

#include "core/interrupt.h"
#include "core/memory_budget.h"
#include "distributed/session.h"
#include "file_access.h"
#include "film/image_io.h"
#include "progress.h"
#include "render_metadata.h"
#include "render/render_control.h"
#include "render/render_isa.h"
#include "render/render_settings.h"
#include "runtime.h"
#include "scene_stats.h"
#include "script_limits.h"
#include "simd/simd_target.h"
#include "types.h"

namespace torte::lua {

namespace {

// Passes progress on to `inner` (or nowhere), and once a render has run for a second starts loading the image
// module (OpenImageIO's ~250 libraries: half a second of dynamic linking) on a background thread, so the image
// output after a long render does not wait for it. Short renders (tests, previews) do not load a module they may
// never use, nor do the ranks of a distributed render that write no image (all but rank 0).
class PreloadImageIo : public ProgressSink {
 public:
  explicit PreloadImageIo(ProgressSink* inner) : inner_(inner) {}
  void update(uint64_t done, uint64_t total, uint64_t rays, double elapsed) override {
    if (elapsed >= 1 && !started_.exchange(true, std::memory_order_relaxed) && dist::rank() == 0) preload_image_io();
    if (inner_) inner_->update(done, total, rays, elapsed);
  }

 private:
  ProgressSink* inner_;
  std::atomic<bool> started_{false};
};


int l_scene(lua_State* L) {
  auto scene = std::make_shared<SceneBuilder>();
  if (!lua_isnoneornil(L, 1)) {
    KwArgs kw(L, 1, "torte.scene");
    scene->set_accel_options(read_accel_options(kw, {}));
    kw.finish();
  }
  push_object(L, std::move(scene));
  return 1;
}

// Arrays given to scene:add nest at most this deep (a table that contains itself would never end).
constexpr int kMaxAddNesting = 16;

// scene:add(obj, ...): shapes, lights and instances (several at once, or arrays of them).
void add_one(lua_State* L, SceneBuilder& scene, int idx, int depth = 0) {
  if (auto shape = to_object<ShapeDesc>(L, idx)) {
    if (shape->kind == ShapeDesc::Kind::Voxel && shape->voxels)
      for (const auto& cell : shape->voxels->cells)
        if (cell.shapes && cell.shapes->reaches(&scene))
          throw Error("scene:add: this voxel grid's cells place the group it is added to (a group cannot contain "
                      "itself)");
    scene.add_shape(*shape);
  } else if (auto light = to_object<Light>(L, idx)) {
    scene.add_light(*light);
  } else if (auto instance = to_object<InstanceDesc>(L, idx)) {
    if (instance->group && instance->group->reaches(&scene))
      throw Error(instance->group.get() == &scene
                      ? "scene:add: a group cannot contain an instance of itself"
                      : "scene:add: the instance's group already places this group (a group cannot contain itself)");
    scene.add_instance(*instance);
  } else if (to_object<SceneBuilder>(L, idx)) {
    throw Error("scene:add: place a group with torte.instance{group = g, transform = ...} (or build it with "
                "scene:frame)");
  } else if (lua_istable(L, idx) && !lua_getmetatable(L, idx)) {
    if (depth >= kMaxAddNesting)
      throw Error("scene:add: arrays nest more than " + std::to_string(kMaxAddNesting) +
                  " levels deep (does an array contain itself?)");
    luaL_checkstack(L, 2, "scene:add");
    const lua_Integer n = lua_Integer(lua_rawlen(L, idx));
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_rawgeti(L, idx, i);
      add_one(L, scene, lua_gettop(L), depth + 1);
      lua_pop(L, 1);
    }
  } else {
    throw Error("scene:add expects shapes, lights and instances, got " + type_name(L, idx));
  }
}

// torte.group(): a container of shapes and instances to place many times (a scene object; see scene:frame).
int l_group(lua_State* L) {
  push_object(L, std::make_shared<SceneBuilder>());
  return 1;
}

// torte.instance{group = g, transform = T}: one placement of a group.
int l_instance(lua_State* L) {
  KwArgs kw(L, 1, "torte.instance");
  auto inst = std::make_shared<InstanceDesc>();
  inst->group = kw.object<SceneBuilder>("group");
  inst->transform = kw.transform("transform");
  kw.finish();
  const float det = inst->transform.determinant3();
  if (!(std::fabs(det) > 0) || !std::isfinite(det)) kw.fail("transform", "is singular or not finite");
  push_object(L, std::move(inst));
  return 1;
}

// scene:frame([transform,] function(g) ... end): a new group filled by the function (called with the group),
// placed in the scene with the transform (identity by default). Returns the group, to place it again with
// torte.instance. Frames nest: call g:frame inside.
int scene_frame(lua_State* L) {
  auto scene = to_object<SceneBuilder>(L, 1);
  if (!scene) throw Error("scene:frame must be called with ':' on a scene or group");
  Transform transform;
  int fn = 2;
  if (!lua_isfunction(L, 2)) {
    auto t = to_object<Transform>(L, 2);
    if (!t) throw Error("scene:frame expects (transform, function) or (function), got " + type_name(L, 2));
    transform = *t;
    fn = 3;
  }
  if (!lua_isfunction(L, fn)) throw Error("scene:frame expects a function that fills the frame, got " + type_name(L, fn));
  auto group = std::make_shared<SceneBuilder>();
  lua_pushvalue(L, fn);
  push_object(L, group);
  lua_call(L, 1, 0);
  if (group->reaches(scene.get()))
    throw Error("scene:frame: the frame's group places the scene or group it is framed in (a group cannot "
                "contain itself)");
  scene->add_instance({group, transform});
  push_object(L, std::move(group));
  return 1;
}

int scene_add(lua_State* L) {
  auto scene = to_object<SceneBuilder>(L, 1);
  if (!scene) throw Error("scene:add must be called with ':' on a scene");
  if (lua_gettop(L) < 2) throw Error("scene:add expects at least one shape or light");
  for (int i = 2; i <= lua_gettop(L); ++i) add_one(L, *scene, i);
  lua_settop(L, 1);
  return 1;  // the scene, so calls can chain
}

// A filter's own range errors ("box filter radius must be ...") prefixed with the function that was called.
template <class Make>
Filter checked_filter(const KwArgs& kw, Make&& make) {
  try {
    return make();
  } catch (const Error& e) {
    throw Error(kw.function() + ": " + e.what());
  }
}

Filter make_filter(lua_State* L, const char* fn, FilterKind kind) {
  if (lua_isnoneornil(L, 1)) {
    lua_settop(L, 0);
    lua_newtable(L);
  }
  KwArgs kw(L, 1, fn);
  switch (kind) {
    case FilterKind::Box: {
      const float r = float(kw.number("radius", 0.5));
      kw.finish();
      return checked_filter(kw, [&] { return Filter::box(r); });
    }
    case FilterKind::Triangle: {
      const float r = float(kw.number("radius", 1));
      kw.finish();
      return checked_filter(kw, [&] { return Filter::triangle(r); });
    }
    case FilterKind::Gaussian: {
      const float r = float(kw.number("radius", 1.5)), sigma = float(kw.number("sigma", 0.5));
      kw.finish();
      return checked_filter(kw, [&] { return Filter::gaussian(r, sigma); });
    }
    case FilterKind::Mitchell: {
      const float r = float(kw.number("radius", 2)), b = float(kw.number("b", 1.0 / 3)),
                  c = float(kw.number("c", 1.0 / 3));
      kw.finish();
      return checked_filter(kw, [&] { return Filter::mitchell(r, b, c); });
    }
  }
  throw Error("internal: unknown filter");
}

template <FilterKind K>
int l_filter(lua_State* L) {
  static constexpr const char* names[] = {"torte.filter.box", "torte.filter.triangle", "torte.filter.gaussian",
                                          "torte.filter.mitchell"};
  push_object(L, std::make_shared<Filter>(make_filter(L, names[int(K)], K)));
  return 1;
}

void print_summary(const RenderedImage& img, const RenderSettings& s) {
  const RenderStats& st = img.stats;
  const double mrays = st.render_seconds > 0 ? double(st.rays()) / st.render_seconds * 1e-6 : 0;
  char reused[64];  // a reused scene costs only its fingerprint: show that it is ~0, not "0.0 s"
  std::snprintf(reused, sizeof reused, "%.2f ms (scene unchanged, reused)", img.build_seconds * 1e3);
  std::fprintf(stderr,
               "render %dx%d, %d spp%s: build %s, render %s; %.1f M rays (camera %.1f M, extension %.1f M, shadow "
               "%.1f M), %.2f Mrays/s; %llu NaN/Inf samples dropped; SIMD %s (render loop %s)\n",
               s.width, s.height, s.spp, st.interrupted ? " (INTERRUPTED: partial image)" : "",
               img.scene_reused ? reused : format_duration(img.build_seconds).c_str(),
               format_duration(st.render_seconds).c_str(),
               double(st.rays()) * 1e-6, double(st.camera_rays) * 1e-6, double(st.extension_rays) * 1e-6,
               double(st.shadow_rays) * 1e-6, mrays, static_cast<unsigned long long>(st.dropped_samples),
               simd::current_target().c_str(), render_isa::selected_name());
  if (st.time_limited)
    std::fprintf(stderr, "time_limit %s reached: stopped after %d of %d spp\n", format_duration(s.time_limit).c_str(),
                 st.spp_reached, s.spp);
  if (!img.pixel_spp.empty()) {  // adaptive sampling: how the samples were spread
    std::vector<uint32_t> spp = img.pixel_spp;
    std::sort(spp.begin(), spp.end());
    const double mean = double(st.samples_done) / double(spp.size());
    const auto at = [&](double q) { return spp[std::min(spp.size() - 1, size_t(q * double(spp.size())))]; };
    std::fprintf(stderr,
                 "adaptive sampling (noise_threshold %g): spp per pixel min %u, 10 %% %u, median %u, 90 %% %u, max %u, "
                 "mean %.1f (%.0f %% of %d spp everywhere)\n",
                 double(s.noise_threshold), spp.front(), at(0.1), at(0.5), at(0.9), spp.back(), mean,
                 100.0 * mean / double(s.spp), s.spp);
  }
  if (st.units > 0)
    std::fprintf(stderr, "distributed over %d ranks: %.1f %% of the %llu units (tile, pass) rendered by ranks 1-%d\n",
                 dist::ranks(), 100.0 * double(st.remote_units) / double(st.units),
                 static_cast<unsigned long long>(st.units), dist::ranks() - 1);
  if (!img.image.layers.empty()) {
    std::string names;
    for (const ImageLayer& l : img.image.layers) names += (names.empty() ? "" : ", ") + l.name;
    std::fprintf(stderr, "layers %s: %s\n", names.c_str(), format_duration(img.aov_seconds).c_str());
  }
}

// Size of what is traced: the scene's own triangles, what instancing places, and the memory it all takes.
void print_scene_summary(const Scene& scene) {
  uint64_t instanced = 0;
  for (const Instance& inst : scene.instances) instanced += scene.prototypes[inst.prototype]->geometry.primitive_count();
  std::fprintf(stderr, "scene: %llu primitives", static_cast<unsigned long long>(scene.primitive_count()));
  if (!scene.instances.empty())
    std::fprintf(stderr, " + %zu instances of %zu groups (%llu primitives placed)", scene.instances.size(),
                 scene.prototypes.size(), static_cast<unsigned long long>(instanced));
  std::fprintf(stderr, "; %zu lights", scene.lights.size());
  size_t patches = 0;  // emitting voxel faces and cell triangles (one light per grid)
  for (const Light& l : scene.lights)
    if (l.kind == LightKind::Patches) patches += l.patches->size();
  if (patches > 0) std::fprintf(stderr, " (%zu emitting voxel patches)", patches);
  std::fprintf(stderr, "; memory: geometry %.1f MB, acceleration %.1f MB\n", double(scene.geometry_bytes()) * 1e-6,
               double(scene.accel_bytes()) * 1e-6);
  // Bytes per triangle of the top-level triangles by part; mesh triples and normals count each source once.
  const double tris = scene.triangle_count();
  if (tris > 0) {
    const ShapeSet::TriangleMemory m = scene.accel().root().triangle_memory();
    size_t indices = 0, normals = 0;
    std::unordered_set<const void*> seen;
    for (const TriangleMesh& mesh : scene.meshes) {
      normals += mesh.nx.size() * 3 * sizeof(float);
      if (seen.insert(&mesh.triple_array()).second) indices += mesh.triple_array().size() * sizeof(uint32_t);
    }
    std::fprintf(stderr,
                 "memory per triangle (%s layout): nodes %.1f B, leaves %.1f B, indices %.1f B (+ %.1f B map), "
                 "normals %.1f B; total %.1f B; peak resident %s\n",
                 bvh_layout_name(scene.accel().layout()), double(m.nodes) / tris, double(m.leaves) / tris,
                 double(indices) / tris, double(m.index_map) / tris, double(normals) / tris,
                 double(m.nodes + m.leaves + indices + m.index_map + normals) / tris,
                 format_bytes(peak_resident_memory()).c_str());
  }
}

// The fields of a render a checkpoint must match: image size, sampling, integrator and its parameters, the
// scene's fingerprint (SceneBuilder::fingerprint, hashed) and which render of the script this is.
std::string checkpoint_key(const RenderSettings& s, const std::string& integrator, const SceneBuilder& scene,
                           int ordinal) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a over the fingerprint's words
  for (const uint64_t w : scene.fingerprint())
    for (int b = 0; b < 64; b += 8) h = (h ^ ((w >> b) & 0xff)) * 1099511628211ull;
  char filter[96];
  std::snprintf(filter, sizeof filter, "%d,%.9g,%.9g,%.9g", int(s.filter.kind()), double(s.filter.radius()),
                double(s.filter.eval_1d(0.25f)), double(s.filter.eval_1d(0.75f)));
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(h));
  return "render=" + std::to_string(ordinal + 1) + ";width=" + std::to_string(s.width) +
         ";height=" + std::to_string(s.height) + ";spp=" + std::to_string(s.spp) + ";integrator=" + integrator +
         ";seed=" + std::to_string(s.seed) + ";max_depth=" + std::to_string(s.max_depth) +
         ";rr_depth=" + std::to_string(s.rr_depth) + ";sample_all_lights=" + std::to_string(s.sample_all_lights) +
         ";tile_size=" + std::to_string(s.tile_size) + ";filter=" + filter + ";vpl_sets=" + std::to_string(s.vpl_sets) +
         ";light_paths=" + std::to_string(s.light_paths) + ";g_limit=" + std::to_string(s.g_limit) +
         ";vpl_roulette=" + std::to_string(s.vpl_roulette) + ";radius=" + std::to_string(s.merge_radius) +
         ";alpha=" + std::to_string(s.merge_alpha) + ";pixel_variance=" + std::to_string(s.pixel_variance) +
         ";scene=" + hash;
}

int l_render(lua_State* L) {
  RunContext& ctx = run_context(L);
  KwArgs kw(L, 1, "torte.render");
  auto scene = kw.object<SceneBuilder>("scene");
  auto camera = kw.object<CameraDesc>("camera");
  RenderSettings s;
  s.width = kw.integer("width", 512);
  s.height = kw.integer("height", 512);
  s.spp = kw.integer("spp", 16);
  s.max_depth = kw.integer("max_depth", 64);
  s.rr_depth = kw.integer("rr_depth", 3);
  s.tile_size = kw.integer("tile_size", 16);
  const std::string integrator = kw.string("integrator", "path");
  if (integrator == "path") {
    s.integrator = IntegratorKind::Path;
  } else if (integrator == "direct") {
    s.integrator = IntegratorKind::Direct;
  } else if (integrator == "igi") {
    s.integrator = IntegratorKind::Igi;
  } else if (integrator == "lt") {
    s.integrator = IntegratorKind::Lt;
  } else if (integrator == "bdpt") {
    s.integrator = IntegratorKind::Bdpt;
  } else if (integrator == "vcm") {
    s.integrator = IntegratorKind::Vcm;
  } else if (integrator == "ppm") {
    s.integrator = IntegratorKind::Ppm;
  } else if (integrator == "mlt") {
    s.integrator = IntegratorKind::Mlt;
  } else {
    kw.fail("integrator", "must be \"path\", \"direct\", \"igi\", \"lt\", \"bdpt\", \"vcm\", \"ppm\" or \"mlt\", got \"" +
                              integrator + "\"");
  }
  // The seed's direct-lighting renderer samples every light at every hit; path tracing picks one by power. igi
  // handles direct light as direct does.
  s.sample_all_lights = kw.boolean("sample_all_lights", ends_after_first_scatter(s.integrator));
  // The one light of next-event estimation: by the light BVH from the shading point, or by power alone.
  if (const std::string ls = kw.string("light_sampler", "bvh"); ls == "power") s.light_sampler = LightSamplerKind::Power;
  else if (ls != "bvh") kw.fail("light_sampler", "must be \"bvh\" or \"power\", got \"" + ls + "\"");
  // Instant global illumination (render/igi.h); accepted (and checked) with any integrator, used by igi only.
  s.vpl_sets = kw.integer("vpl_sets", s.vpl_sets);
  s.light_paths = kw.integer("light_paths", s.light_paths);
  s.g_limit = float(kw.number("g_limit", s.g_limit));
  s.vpl_roulette = float(kw.number("vpl_roulette", s.vpl_roulette));
  // Vertex connection and merging, progressive photon mapping (render/integrator_vcm.h); checked always.
  s.merge_radius = float(kw.number("radius", s.merge_radius));
  s.merge_alpha = float(kw.number("alpha", s.merge_alpha));
  // Metropolis light transport (render/integrator_mlt.h); checked always.
  s.large_step = float(kw.number("large_step", s.large_step));
  s.chains = kw.integer("chains", s.chains);
  // Adaptive sampling and a time budget (render/adaptive_sampling.h, render/tile_loop.h).
  s.noise_threshold = float(kw.number("noise_threshold", 0));
  s.adaptive_min_spp = kw.integer("adaptive_min_spp", s.adaptive_min_spp);
  s.time_limit = kw.number("time_limit", 0);
  const int seed = kw.integer("seed", 0);
  if (seed < 0) kw.fail("seed", "must be a non-negative integer");
  s.seed = uint64_t(seed);
  if (auto f = kw.object<Filter>("filter", true)) s.filter = *f;
  // The per-stage profile (image.stages); --stats collects it for every render and prints it.
  s.stage_stats = kw.boolean("stats", false) || ctx.stats;
  AovRequest aov_request = read_aov_request(kw, s.spp);
  const AccelOptions accel_options = read_accel_options(kw, scene->accel_options());
  kw.finish();
  aov_request.aovs.insert(aov_request.aovs.end(), ctx.aovs.begin(), ctx.aovs.end());
  aov_request.denoise = aov_request.denoise || ctx.denoise;
  // The rules are render()'s (render/render_settings.h); checked here to name the keyword before the build.
  if (const auto problem = find_settings_problem(s)) kw.fail(problem->key, problem->problem);
  if (s.integrator == IntegratorKind::Lt)  // light paths connect to the camera: it must allow that
    if (const std::string why = Camera(*camera, s.width, s.height).connect_problem(); !why.empty())
      kw.fail("camera", "cannot be used with integrator \"lt\": " + why);
  if (s.integrator == IntegratorKind::Bdpt || s.integrator == IntegratorKind::Vcm ||
      s.integrator == IntegratorKind::Ppm || s.integrator == IntegratorKind::Mlt) {  // as lt, and perspective only (integrator_bdpt.h, integrator_vcm.h)
    const Camera cam(*camera, s.width, s.height);
    const std::string name = integrator_name(s.integrator);
    std::string why = cam.connect_problem();
    if (why.empty() && cam.desc().kind != CameraKind::Perspective) why = name + " needs a perspective camera";
    if (!why.empty()) kw.fail("camera", "cannot be used with integrator \"" + name + "\": " + why);
  }
  if (ctx.list_args) {  // --list-args and the script renders before it calls torte.options: it declares none
    lua_newtable(L);
    list_arguments(L, lua_gettop(L));
  }
  if (ctx.quick) {  // --quick (runtime.h)
    s.width = (s.width + kQuickDivisor - 1) / kQuickDivisor;
    s.height = (s.height + kQuickDivisor - 1) / kQuickDivisor;
    s.spp = std::min(s.spp, kQuickSpp);
  }
  if (ctx.spp_override > 0) s.spp = ctx.spp_override;
  if (ctx.seed_override >= 0) s.seed = uint64_t(ctx.seed_override);
  if (ctx.time_limit_override) s.time_limit = *ctx.time_limit_override;
  if (ctx.noise_threshold_override) s.noise_threshold = *ctx.noise_threshold_override;
  if (ctx.noise_threshold_override || ctx.spp_override > 0 || ctx.quick)  // the rules again, for the overrides
    if (const auto problem = find_settings_problem(s)) throw Error("torte.render: " + problem->message());
  // The film's moments, for the denoiser's noise level or the "variance" AOV.
  const bool variance_aov =
      std::find(aov_request.aovs.begin(), aov_request.aovs.end(), Aov::Variance) != aov_request.aovs.end();
  if (variance_aov && splats_to_film(s.integrator))
    kw.fail("aovs", std::string("\"variance\" needs a camera integrator (path, direct or igi): ") +
                        integrator_name(s.integrator) +
                        " adds light to pixels from other pixels' paths");
  s.pixel_variance = aov_request.denoise || variance_aov;
  if (ctx.interrupted || interrupt_requested()) throw Interrupted("interrupted: torte.render was not started");
  // The film is checked before the scene is built, so an over-large image fails at once.
  reserve_memory(render_memory_bytes(s), "torte.render: the " + std::to_string(s.width) + "x" +
                                             std::to_string(s.height) + " image's film");

  const auto t0 = std::chrono::steady_clock::now();
  const SceneCache::Lookup built = cached_scene(L, *scene, "torte.render", &accel_options);
  const Scene& flat = *built.scene;
  if (const std::string why = black_image_reason(flat); !why.empty()) {
    luaL_where(L, 1);
    std::fprintf(stderr, "torte: warning: %storte.render: %s\n", lua_tostring(L, -1), why.c_str());
    lua_pop(L, 1);
  }
  const double build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Checkpoints: the key names what the image depends on, so a resume of another render is refused.
  RenderControl control;
  if (!ctx.checkpoint.empty() || !ctx.resume.empty()) {
    control.checkpoint = ctx.checkpoint;
    control.checkpoint_every = ctx.checkpoint_every;
    control.resume = ctx.resume;
    control.key = checkpoint_key(s, integrator, *scene, ctx.renders);
    s.control = &control;
  }
  ConsoleProgress progress("render");
  PreloadImageIo progress_and_preload(ctx.quiet ? nullptr : &progress);
  auto img = std::make_shared<RenderedImage>();
  RenderOutput out;
  try {
    out = render(flat, Camera(*camera, s.width, s.height), s, &progress_and_preload, ctx.cancel);
  } catch (...) {
    progress.finish();
    throw;
  }
  progress.finish();
  img->image = std::move(out.image);
  img->image.attributes = render_attributes(s, integrator, *camera, out.stats);
  img->stats = out.stats;
  img->pixel_spp = std::move(out.pixel_spp);
  img->variance = std::move(out.variance);
  if (!out.stats.interrupted && !interrupt_requested()) {  // Ctrl-C: keep what the render made, nothing more
    const auto t_aov = std::chrono::steady_clock::now();
    add_aovs(*img, flat, Camera(*camera, s.width, s.height), s, aov_request, ctx.cancel);
    img->aov_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_aov).count();
  }
  img->build_seconds = build_seconds;
  img->scene_reused = built.reused;
  if (out.stats.interrupted || interrupt_requested()) {  // Ctrl-C: the script may still save this image
    ctx.interrupted = true;
    note_render_interrupted(L);
  }
  ctx.build_seconds += build_seconds;
  ctx.render_seconds += out.stats.render_seconds;
  ctx.rays += out.stats.rays();
  ctx.dropped_samples += out.stats.dropped_samples;
  ++ctx.renders;
  if (!ctx.quiet) print_scene_summary(flat);
  // --quiet still reports a stopped render; in a distributed one only rank 0 speaks for the frame.
  if (!ctx.quiet || (out.stats.interrupted && dist::rank() == 0)) print_summary(*img, s);
  if (ctx.stats)  // --stats: the scene's statistics before the stage table
    std::fputs(format_scene_statistics(scene_statistics(flat, build_seconds, built.reused)).c_str(), stderr);
  if (ctx.stats) std::fputs(format_stage_table(out.stats.stages, out.stats.render_seconds).c_str(), stderr);
  if (out.stats.dropped_samples > 0 && ctx.quiet)
    std::fprintf(stderr, "warning: %llu NaN/Inf samples were dropped\n",
                 static_cast<unsigned long long>(out.stats.dropped_samples));
  push_object(L, std::move(img));
  return 1;
}

}  // namespace

void open_render(lua_State* L, int torte_index) {
  // Metatables get their methods once; push_object creates them on first use, so make one of each now.
  push_object(L, std::make_shared<SceneBuilder>());
  lua_getmetatable(L, -1);
  lua_newtable(L);
  lua_pushcfunction(L, guarded<scene_add>);
  lua_setfield(L, -2, "add");
  lua_pushcfunction(L, guarded<scene_frame>);
  lua_setfield(L, -2, "frame");
  lua_pushcfunction(L, guarded<scene_stats>);  // lua/scene_stats.h
  lua_setfield(L, -2, "stats");
  lua_setfield(L, -2, "__index");
  lua_pop(L, 2);

  const luaL_Reg fns[] = {{"scene", guarded<l_scene>},
                          {"group", guarded<l_group>},
                          {"instance", guarded<l_instance>},
                          {"render", guarded<l_render>},
                          {nullptr, nullptr}};
  lua_pushvalue(L, torte_index);
  set_functions(L, fns);
  lua_pop(L, 1);
  const luaL_Reg filters[] = {{"box", guarded<l_filter<FilterKind::Box>>},
                              {"triangle", guarded<l_filter<FilterKind::Triangle>>},
                              {"gaussian", guarded<l_filter<FilterKind::Gaussian>>},
                              {"mitchell", guarded<l_filter<FilterKind::Mitchell>>},
                              {nullptr, nullptr}};
  push_subtable(L, torte_index, "filter");
  set_functions(L, filters);
  lua_pop(L, 1);
}

}  // namespace torte::lua
