#include "render/render.h"


#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/parallel.h"
#include "render/igi.h"
#include "render/wavefront.h"

namespace torte {

namespace {

struct Tile {
  int x0, y0, x1, y1;
};

std::vector<Tile> make_tiles(int width, int height, int size) {
  std::vector<Tile> tiles;
  for (int y = 0; y < height; y += size)
    for (int x = 0; x < width; x += size) tiles.push_back({x, y, std::min(x + size, width), std::min(y + size, height)});
  return tiles;
}

// Samples per pixel in each progressive pass: small first passes give an early full-frame image (and something
// to write if the render is interrupted), later ones keep wavefront batches large.
std::vector<int> make_passes(int spp) {
  std::vector<int> passes;
  int done = 0, size = 1;
  while (done < spp) {
    const int n = std::min(size, spp - done);
    passes.push_back(n);
    done += n;
    size = std::min(size * 2, 16);
  }
  return passes;
}

void validate(const Scene& scene, const RenderSettings& s) {
  if (!scene.has_camera) throw Error("the scene has no camera");
  if (s.width <= 0 || s.height <= 0) throw Error("image width and height must be positive");
  if (uint64_t(s.width) * uint64_t(s.height) > kMaxRenderPixels)
    throw Error("a " + std::to_string(s.width) + "x" + std::to_string(s.height) + " image has " +
                std::to_string(uint64_t(s.width) * uint64_t(s.height)) + " pixels, more than the limit of " +
                std::to_string(kMaxRenderPixels) + " (2^28)");
  if (s.spp <= 0 || s.spp > kMaxSpp)
    throw Error("spp must be in [1, " + std::to_string(kMaxSpp) + "], got " + std::to_string(s.spp));
  if (s.max_depth < 0 || s.max_depth > 10000) throw Error("max_depth must be in [0, 10000]");
  if (s.tile_size <= 0) throw Error("tile size must be positive");
  if (s.vpl_sets < 1 || s.vpl_sets > 65536) throw Error("vpl_sets must be in [1, 65536]");
  if (s.light_paths < 1 || s.light_paths > (1 << 24)) throw Error("light_paths must be in [1, 2^24]");
  if (!(s.g_limit > 0)) throw Error("g_limit must be positive (infinity disables the clamp)");
  if (!(s.vpl_roulette >= 0 && s.vpl_roulette <= 1)) throw Error("vpl_roulette must be in [0, 1]");
}

// A failed image lookup returns black: the render stops and fails naming the file instead of writing that.
std::string texture_failure(const Scene& scene) {
  for (const auto& image : scene.textures.images())
    if (std::string f = image->failure(); !f.empty()) return f;
  return {};
}

}  // namespace

uint64_t render_memory_bytes(const RenderSettings& s) {
  const uint64_t pixels = uint64_t(std::max(s.width, 0)) * uint64_t(std::max(s.height, 0));
  return pixels * (sizeof(PixelSum) + sizeof(Rgb));  // the film, then the image made from it
}

RenderOutput render(const Scene& scene, const RenderSettings& settings, ProgressSink* progress,
                    const std::atomic<bool>* cancel) {
  validate(scene, settings);
  reserve_memory(render_memory_bytes(settings),
                 "the " + std::to_string(settings.width) + "x" + std::to_string(settings.height) + " image's film");
  const auto start = std::chrono::steady_clock::now();
  const Camera camera(scene.camera, settings.width, settings.height);
  const Sampler sampler(settings.seed);
  const std::vector<Tile> tiles = make_tiles(settings.width, settings.height, settings.tile_size);
  std::vector<PixelSum> film(size_t(settings.width) * settings.height);
  // IGI's preprocess: the virtual point lights, shared read-only by every tile.
  const VplStore vpls = settings.integrator == IntegratorKind::Igi ? generate_vpls(scene, settings) : VplStore{};
  const VplStore* vpl_ptr = settings.integrator == IntegratorKind::Igi ? &vpls : nullptr;

  struct Worker {
    std::unique_ptr<WavefrontRenderer> renderer;
    std::vector<SampleRequest> requests;
    RenderStats stats;
  };
  PerThread<Worker> workers;
  std::atomic<uint64_t> samples_done{0}, rays_done{0};
  const uint64_t samples_total = uint64_t(settings.width) * settings.height * settings.spp;
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  auto cancelled = [&] { return cancel && cancel->load(std::memory_order_relaxed); };
  const bool has_images = !scene.textures.images().empty();
  auto texture_failed = [&] { return has_images && !texture_failure(scene).empty(); };

  int first_sample = 0;
  for (const int pass_spp : make_passes(settings.spp)) {
    if (cancelled() || texture_failed()) break;
    parallel_for_blocks(size_t(0), tiles.size(), 1, [&](IndexRange<size_t> range) {
      Worker& w = workers.local();
      if (!w.renderer) w.renderer = std::make_unique<WavefrontRenderer>(scene, camera, settings, sampler, vpl_ptr);
      for (size_t t = range.begin(); t != range.end(); ++t) {
        if (cancelled() || texture_failed()) return;
        const Tile& tile = tiles[t];
        w.requests.clear();
        for (int y = tile.y0; y < tile.y1; ++y)
          for (int x = tile.x0; x < tile.x1; ++x)
            for (int s = first_sample; s < first_sample + pass_spp; ++s)
              w.requests.push_back({uint32_t(y) * uint32_t(settings.width) + uint32_t(x), uint32_t(s)});
        const uint64_t rays_before = w.stats.rays();
        w.renderer->render(w.requests, film, w.stats);
        const uint64_t done = samples_done += w.requests.size();
        const uint64_t rays = rays_done += w.stats.rays() - rays_before;
        if (progress) progress->update(done, samples_total, rays, elapsed());
      }
    }, Split::each_block);
    first_sample += pass_spp;
  }

  if (const std::string failure = texture_failure(scene); !failure.empty()) throw Error(failure);
  RenderOutput out;
  out.stats.extension_rays += vpls.light_rays;  // IGI's light paths
  for (const Worker& w : workers) {
    out.stats.camera_rays += w.stats.camera_rays;
    out.stats.extension_rays += w.stats.extension_rays;
    out.stats.shadow_rays += w.stats.shadow_rays;
    out.stats.dropped_samples += w.stats.dropped_samples;
    out.stats.samples_done += w.stats.samples_done;
  }
  out.stats.interrupted = cancelled() && out.stats.samples_done < samples_total;
  out.image = Image(settings.width, settings.height);
  for (size_t i = 0; i < film.size(); ++i)
    out.image.pixels[i] = film[i].weight != 0 ? film[i].weighted / film[i].weight : Rgb(0);
  out.stats.render_seconds = elapsed();
  return out;
}

}  // namespace torte
