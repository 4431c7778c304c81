#include "render/integrator_vcm.h"

#include <numbers>

#include "core/error.h"
#include "core/parallel.h"
#include "light/light_emission.h"
#include "render/bdpt_connect.h"
#include "render/bdpt_subpath.h"
#include "render/bdpt_subpaths.h"
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
  VcmTracer(const Scene& scene, const Camera& camera, const RenderSettings& image, const Sampler& sampler,
            const VcmSettings& vcm, const Photons& photons)
      : scene_(scene), camera_(camera), image_(image), vcm_(vcm), rules_(vcm.rules()),
        photons_(photons), connector_(scene, camera, sampler, {vcm.max_depth, -1, -1, 0.0, vcm.connect}),
        subpaths_(scene, rules_, sampler) {}

  // The light subpaths of `requests` into `store` (light vertex 0, then every surface vertex).
  void trace_light(std::span<const SampleRequest> requests, BdptStore& store, RenderStats& stats) {
    subpaths_.start_light(requests, lpaths_, store);
    // The last light vertex (depth max_depth - 1) only connects to the camera or merges: they stop there.
    if (vcm_.max_depth > 0)
      subpaths_.advance(lpaths_, store, TransportMode::Importance, kDimLightSubpathBase, 0.0f, vcm_.max_depth,
                        false, stats, clock_);
    else
      subpaths_.drop_rays();
  }

  void render(std::span<const SampleRequest> requests, Film& film, RenderStats& stats, SplatBuffer& splats) {
    StageStats& st = stats.stages;
    clock_ = StageClock(st.enabled);
    clock_.start();
    subpaths_.start_camera(requests, camera_, image_, cpaths_, camera_store_);
    stats.camera_rays += requests.size();
    clock_.lap(st[Stage::Camera], requests.size());
    subpaths_.advance(cpaths_, camera_store_, TransportMode::Radiance, 0, camera_.spread_angle(), vcm_.max_depth + 1,
                      true, stats, clock_);
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

  const Scene& scene_;
  const Camera& camera_;
  const RenderSettings& image_;
  VcmSettings vcm_;
  TransportRules rules_;
  const Photons& photons_;
  BdptConnector connector_;
  PathState lpaths_, cpaths_;
  BdptStore camera_store_;
  BdptSubpaths subpaths_;
  ShadowQueue shadows_;
  CameraQueue splat_queue_;
  std::vector<uint8_t> occluded_;
  std::vector<uint32_t> chain_;
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
