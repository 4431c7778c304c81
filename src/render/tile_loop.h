// Progressive passes over image tiles (TBB), shared by every camera-path integrator. A Driver provides:
//   void begin_pass(int first_sample, int pass_spp);  // serial, before the pass (IGI draws its VPLs here)
//   std::unique_ptr<Worker> make_worker();             // one per thread; Worker::render(requests, film, stats)
//   void finish(RenderStats&);                          // adds the driver's own counts (e.g. light-path rays)
// A Worker whose render takes a fourth argument, a SplatBuffer&, splats (light tracing): every tile gets its own
// buffer, merged into the film in tile order as soon as the tiles before it are merged (so few buffers wait),
// and the image adds the splat sums * width * height / (samples done): each sample stands for one light path.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "film/film.h"
#include "render/render.h"
#include "render/stage_camera.h"

namespace torte {

namespace detail {
struct Tile {
  int x0, y0, x1, y1;
};
std::vector<Tile> make_tiles(int width, int height, int size);
// Samples per pixel in each progressive pass: small first passes give an early full-frame image (and something
// to write if the render is interrupted), later ones keep wavefront batches large.
std::vector<int> make_passes(int spp);
// Camera samples per wavefront: a tile's pass is rendered in wavefronts of at most this many paths, so that the
// paths' state, queues and shading scratch (~450 bytes a path) stay in a core's L2 cache (1 MB on the EPYC);
// at 4096 they spilled, and the simulated L2 misses halved at 1024 (bench/RESULTS.md). Chunks keep request
// order, so the film sums every pixel's samples in the same order: the image does not change.
inline constexpr size_t kWavefrontSamples = 1024;
// The first image texture that failed to read ("" if none): the render then stops and fails naming the file.
std::string texture_failure(const Scene& scene);
}  // namespace detail

template <class Driver>
RenderOutput run_tiles(const Scene& scene, const RenderSettings& settings, Driver& driver, ProgressSink* progress,
                       const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<detail::Tile> tiles = detail::make_tiles(settings.width, settings.height, settings.tile_size);
  Film film(settings.width, settings.height);
  using Worker = typename decltype(driver.make_worker())::element_type;
  struct Slot {
    std::unique_ptr<Worker> worker;
    std::vector<SampleRequest> requests;
    RenderStats stats;
  };
  PerThread<Slot> slots;
  std::atomic<uint64_t> samples_done{0}, rays_done{0};
  const uint64_t samples_total = uint64_t(settings.width) * settings.height * settings.spp;
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  auto cancelled = [&] { return cancel && cancel->load(std::memory_order_relaxed); };
  const bool has_images = !scene.textures.images().empty();
  auto texture_failed = [&] { return has_images && !detail::texture_failure(scene).empty(); };

  constexpr bool kSplats = requires(Worker& w, std::span<const SampleRequest> r, Film& f, RenderStats& st,
                                    SplatBuffer& b) { w.render(r, f, st, b); };
  std::vector<SplatBuffer> splats(kSplats ? tiles.size() : 0);
  std::vector<uint8_t> tile_done(splats.size());
  size_t next_merge = 0;  // the first tile of the pass whose splats are not merged yet
  std::mutex merge_mutex;
  // Merges the finished tiles that follow the merged ones, in tile order (`all`: also past unfinished ones, at
  // the end of a pass, when an interruption left tiles undone).
  auto merge_ready = [&](bool all) {
    for (; next_merge < splats.size() && (all || tile_done[next_merge]); ++next_merge) {
      if (tile_done[next_merge]) film.merge_splats(splats[next_merge]);
      splats[next_merge] = SplatBuffer();  // frees its memory
    }
  };

  int first_sample = 0;
  for (const int pass_spp : detail::make_passes(settings.spp)) {
    if (cancelled() || texture_failed()) break;
    driver.begin_pass(first_sample, pass_spp);
    std::fill(tile_done.begin(), tile_done.end(), uint8_t(0));
    next_merge = 0;
    parallel_for_blocks(size_t(0), tiles.size(), 1, [&](IndexRange<size_t> range) {
      Slot& w = slots.local();
      if (!w.worker) {
        w.worker = driver.make_worker();
        w.stats.stages.enabled = settings.stage_stats;
      }
      for (size_t t = range.begin(); t != range.end(); ++t) {
        if (cancelled() || texture_failed()) return;
        const detail::Tile& tile = tiles[t];
        w.requests.clear();
        for (int y = tile.y0; y < tile.y1; ++y)
          for (int x = tile.x0; x < tile.x1; ++x)
            for (int s = first_sample; s < first_sample + pass_spp; ++s)
              w.requests.push_back({uint32_t(y) * uint32_t(settings.width) + uint32_t(x), uint32_t(s)});
        const uint64_t rays_before = w.stats.rays();
        const std::span<const SampleRequest> all(w.requests);
        for (size_t b = 0; b < all.size(); b += detail::kWavefrontSamples) {
          const auto chunk = all.subspan(b, std::min(detail::kWavefrontSamples, all.size() - b));
          if constexpr (kSplats) {
            w.worker->render(chunk, film, w.stats, splats[t]);  // chunks in order: the tile's splats keep theirs
          } else {
            w.worker->render(chunk, film, w.stats);
          }
        }
        if constexpr (kSplats) {
          const std::lock_guard<std::mutex> lock(merge_mutex);
          tile_done[t] = 1;
          merge_ready(false);
        }
        const uint64_t done = samples_done += w.requests.size();
        const uint64_t rays = rays_done += w.stats.rays() - rays_before;
        if (progress) progress->update(done, samples_total, rays, elapsed());
      }
    }, Split::each_block);
    if constexpr (kSplats) merge_ready(true);
    first_sample += pass_spp;
  }

  if (const std::string failure = detail::texture_failure(scene); !failure.empty()) throw Error(failure);
  RenderOutput out;
  for (const Slot& w : slots) {
    out.stats.add(w.stats);
    if (w.worker) ++out.stats.stages.threads;
  }
  out.stats.stages.enabled = settings.stage_stats;
  driver.finish(out.stats);
  out.stats.interrupted = cancelled() && out.stats.samples_done < samples_total;
  const uint64_t pixels = uint64_t(settings.width) * uint64_t(settings.height);
  out.image = film.image(kSplats && out.stats.samples_done > 0 ? float(double(pixels) / double(out.stats.samples_done))
                                                               : 1.0f);
  out.stats.render_seconds = elapsed();
  return out;
}

}  // namespace torte
