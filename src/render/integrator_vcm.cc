#include "render/integrator_vcm.h"

#include <numbers>

#include "core/error.h"
#include "core/parallel.h"
#include "light/light_emission.h"
#include "render/bdpt_connect.h"
#include "render/bdpt_subpath.h"
#include "render/integrator_bdpt.h"
#include "render/stage_camera.h"
#include "render/stage_film.h"
#include "render/stage_hits.h"
#include "render/stage_light.h"
#include "render/stage_trace.h"
#include "render/tile_loop.h"
#include "render/vcm_grid.h"

namespace torte {

namespace {

// Light subpaths of an iteration are traced and stored in chunks of this many pixels (one wavefront each).
constexpr uint32_t kChunk = uint32_t(detail::kWavefrontSamples);

// One iteration's light subpaths and the grid over their surface vertices; written by begin_pass, read by
// every worker during the pass.
struct Photons {
  std::vector<BdptStore> stores;  // by chunk of pixels: the light subpath of pixel p is path p % kChunk
  std::vector<Vec3f> points;      // photon k's position
  std::vector<uint64_t> ids;      // photon k: (chunk << 32) | vertex
  PhotonGrid grid;
  double eta = 0;    // N pi r^2
  float scale = 0;   // the kernel's 1 / (N pi r^2)
};

// The subpaths of one wavefront (light subpaths into a given store, or camera subpaths with their
// connections and merges), advanced as bdpt advances them.
class VcmTracer {
 public:
  template <MaterialType T>
  using Scratch = ShadeScratch<typename MaterialTraits<T>::Bsdf>;

  VcmTracer(const Scene& scene, const Camera& camera, const RenderSettings& image, const Sampler& sampler,
            const VcmSettings& vcm, const Photons& photons)
      : scene_(scene), camera_(camera), image_(image), sampler_(sampler), vcm_(vcm), rules_(vcm.rules()),
        photons_(photons), connector_(scene, camera, sampler, {vcm.max_depth, -1, -1, 0.0, vcm.connect}) {}

  // The light subpaths of `requests` into `store` (light vertex 0, then every surface vertex).
  void trace_light(std::span<const SampleRequest> requests, BdptStore& store, RenderStats& stats) {
    store.clear(requests.size());
    generate_light_rays(requests, scene_, sampler_, lpaths_, rays_, kDimLightSubpathBase,
                        [&](size_t i, int l, float pmf, const EmissionSample& es) {
                          BdptVertex v;
                          v.kind = BdptVertexKind::Light;
                          v.p = es.origin;
                          v.ng = es.normal;
                          v.light = l;
                          v.pdf_fwd = pmf * es.pdf_pos;
                          store.push(v, uint32_t(i));
                          lpaths_.bsdf_pdf[i] = es.pdf_dir;
                        });
    // The last light vertex (depth max_depth - 1) only connects to the camera or merges: they stop there.
    if (vcm_.max_depth > 0)
      advance(lpaths_, store, TransportMode::Importance, kDimLightSubpathBase, 0.0f, vcm_.max_depth, false, stats);
    else
      rays_.clear();
  }

  void render(std::span<const SampleRequest> requests, Film& film, RenderStats& stats, SplatBuffer& splats) {
    StageStats& st = stats.stages;
    clock_ = StageClock(st.enabled);
    clock_.start();
    start_camera_subpaths(requests);
    stats.camera_rays += requests.size();
    clock_.lap(st[Stage::Camera], requests.size());
    advance(cpaths_, camera_store_, TransportMode::Radiance, 0, camera_.spread_angle(), vcm_.max_depth + 1, true,
            stats);
    shadows_.clear();
    splat_queue_.clear();
    connector_.set_eta(vcm_.merge ? photons_.eta : 0.0);
    for (uint32_t i = 0; i < uint32_t(requests.size()); ++i) {
      const uint32_t px = requests[i].pixel;
      const BdptStore& light = photons_.stores[px / kChunk];
      connector_.connect(i, light, px % kChunk, camera_store_, cpaths_, shadows_, splat_queue_);
      if (vcm_.merge && photons_.eta > 0) merge(i);
    }
    clock_.lap(st[Stage::Connect], requests.size());
    trace_shadows(scene_, shadows_, cpaths_, occluded_, stats);
    trace_camera_connections(scene_, splat_queue_, film, splats, occluded_, stats);
    clock_.lap(st[Stage::Shadows], shadows_.size() + splat_queue_.size());
    accumulate_samples(cpaths_, film, stats);
    clock_.lap(st[Stage::Film], cpaths_.size());
  }

 private:
  // Merges every vertex (after the lens) of camera subpath i with the photons near it, summed in the grid's
  // fixed order, so the sum does not depend on the thread count.
  void merge(uint32_t i) {
    const int n = connector_.begin_merges(i, camera_store_);
    camera_store_.chain(i, chain_);
    Rgb sum(0);
    for (int tc = 1; tc < n; ++tc) {
      const BdptVertex& y = camera_store_.vertices[chain_[size_t(tc)]];
      if (!y.connectible) continue;
      photons_.grid.query(y.p, photons_.points, [&](uint32_t k) {
        const uint64_t id = photons_.ids[k];
        sum += connector_.merge(tc, camera_store_, photons_.stores[size_t(id >> 32)], uint32_t(id));
      });
    }
    const Rgb value = sum * photons_.scale;
    if (value.is_finite()) cpaths_.radiance[i] += value;
  }

  void start_camera_subpaths(std::span<const SampleRequest> requests) {
    generate_camera_rays(requests, camera_, image_.filter, image_.width, image_.height, sampler_, cpaths_, rays_);
    camera_store_.clear(requests.size());
    for (size_t k = 0; k < rays_.size(); ++k) {
      const uint32_t i = rays_.path[k];
      BdptVertex v;
      v.kind = BdptVertexKind::Camera;
      v.p = rays_.origin(k);
      v.pdf_fwd = 1;
      camera_store_.push(v, i);
      float pdf_pos, pdf_dir;
      camera_.pdf_we(Ray{rays_.origin(k), rays_.dir(k)}, &pdf_pos, &pdf_dir);
      cpaths_.bsdf_pdf[i] = pdf_dir;
    }
  }

  // As BdptTracer::advance (render/integrator_bdpt.cc): trace, sort, record the vertices, shade per type.
  void advance(PathState& ps, BdptStore& store, TransportMode mode, uint32_t dim_base, float spread,
               int depth_limit, bool camera_rays, RenderStats& stats) {
    StageStats& st = stats.stages;
    for (int bounce = 0; rays_.size() != 0; ++bounce) {
      const bool coherent = camera_rays && bounce == 0;
      trace_rays(scene_, rays_, hits_, coherent);
      if (!coherent) stats.extension_rays += rays_.size();
      clock_.lap(st[Stage::Trace], rays_.size());
      sort_hits(scene_, rules_, sampler_, spread, rays_, hits_, ps, queues_, dim_base);
      record_subpath_hits(scene_, rays_, hits_, ps, mode == TransportMode::Importance, store);
      clock_.lap(st[Stage::Hits], queues_.slots.size());
      next_.clear();
      const ShadeContext ctx{scene_, rules_, sampler_, ps, rays_, hits_, next_, no_shadows_};
      for_each_shaded_type([&](auto t) {
        const std::span<const uint32_t> queue = queues_.queue(t());
        shade_subpath_queue<t()>(ctx, queue, std::get<int(t())>(scratch_), store, mode, dim_base, depth_limit);
        if (!queue.empty()) clock_.lap(st.shade[int(t())], queue.size());
      });
      std::swap(rays_, next_);
    }
  }

  const Scene& scene_;
  const Camera& camera_;
  const RenderSettings& image_;
  const Sampler& sampler_;
  VcmSettings vcm_;
  TransportRules rules_;
  const Photons& photons_;
  BdptConnector connector_;
  PathState lpaths_, cpaths_;
  BdptStore camera_store_;
  RayQueue rays_, next_;
  HitQueue hits_;
  MaterialQueues queues_;
  ShadowQueue no_shadows_;
  ShadowQueue shadows_;
  CameraQueue splat_queue_;
  std::vector<uint8_t> occluded_;
  std::vector<uint32_t> chain_;
  PerShadedType<Scratch> scratch_;
  StageClock clock_;
};

class VcmDriver {
 public:
  struct Worker {
    VcmTracer tracer;
    void render(std::span<const SampleRequest> requests, Film& film, RenderStats& stats, SplatBuffer& splats) {
      tracer.render(requests, film, stats, splats);
    }
  };
  VcmDriver(const Scene& scene, const Camera& camera, const RenderSettings& settings, const VcmSettings& vcm)
      : scene_(scene), camera_(camera), settings_(settings), sampler_(settings.seed), vcm_(vcm) {}

  // One sample per pass: each pass is an iteration, with its own light subpaths, grid and radius.
  std::vector<int> passes(int spp) const { return std::vector<int>(size_t(spp), 1); }

  // Traces the iteration's light subpaths (one per pixel, chunks in parallel) and builds the grid.
  void begin_pass(int first_sample, int) {
    const uint32_t pixels = uint32_t(settings_.width) * uint32_t(settings_.height);
    const size_t chunks = (pixels + kChunk - 1) / kChunk;
    photons_.stores.resize(chunks);
    parallel_for(size_t(0), chunks, [&](size_t c) {
      LightSlot& slot = light_slots_.local();
      if (!slot.tracer) slot.tracer = std::make_unique<VcmTracer>(scene_, camera_, settings_, sampler_, vcm_, photons_);
      slot.requests.clear();
      for (uint32_t p = uint32_t(c) * kChunk; p < std::min(pixels, uint32_t(c + 1) * kChunk); ++p)
        slot.requests.push_back({p, uint32_t(first_sample)});
      slot.tracer->trace_light(slot.requests, photons_.stores[c], slot.stats);
    });
    // The photons: surface vertices of the light subpaths that can scatter light diffusely, in chunk order.
    photons_.points.clear();
    photons_.ids.clear();
    for (size_t c = 0; c < chunks; ++c) {
      const std::vector<BdptVertex>& vs = photons_.stores[c].vertices;
      for (uint32_t v = 0; v < uint32_t(vs.size()); ++v)
        if (vs[v].kind == BdptVertexKind::Surface && vs[v].connectible) {
          photons_.points.push_back(vs[v].p);
          photons_.ids.push_back((uint64_t(c) << 32) | v);
        }
    }
    const float r = vcm_.radius_at(first_sample + 1, scene_.radius());
    const double area = std::numbers::pi * double(r) * double(r);
    photons_.eta = 0;
    photons_.scale = 0;
    if (vcm_.merge && r > 0 && std::isfinite(r) && !photons_.points.empty()) {
      photons_.grid.build(photons_.points, r);
      photons_.eta = double(pixels) * area;
      photons_.scale = float(1 / photons_.eta);
    }
  }

  std::unique_ptr<Worker> make_worker() {
    return std::make_unique<Worker>(Worker{VcmTracer(scene_, camera_, settings_, sampler_, vcm_, photons_)});
  }

  // The light subpaths' rays, traced outside the tiles.
  void finish(RenderStats& stats) {
    for (const LightSlot& slot : light_slots_) stats.extension_rays += slot.stats.extension_rays;
  }

 private:
  struct LightSlot {
    std::unique_ptr<VcmTracer> tracer;
    std::vector<SampleRequest> requests;
    RenderStats stats;
  };
  const Scene& scene_;
  const Camera& camera_;
  const RenderSettings& settings_;
  Sampler sampler_;
  VcmSettings vcm_;
  Photons photons_;
  PerThread<LightSlot> light_slots_;
};

}  // namespace

RenderOutput render_vcm(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                        const VcmSettings& vcm, ProgressSink* progress, const std::atomic<bool>* cancel) {
  const char* name = vcm.connect ? "vcm" : "ppm";
  if (const std::string why = bdpt_problem(scene, camera); !why.empty())
    throw Error(std::string("integrator '") + name + "': " + why);
  VcmDriver driver(scene, camera, settings, vcm);
  return run_tiles(scene, settings, driver, progress, cancel);
}

RenderOutput render_vcm(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                        ProgressSink* progress, const std::atomic<bool>* cancel) {
  return render_vcm(scene, camera, settings, VcmSettings::from(settings), progress, cancel);
}

}  // namespace torte
