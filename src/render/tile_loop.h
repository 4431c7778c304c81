// Progressive passes over image tiles (TBB), shared by every camera-path integrator. A Driver provides:
//   void begin_pass(int first_sample, int pass_spp);  // serial, before the pass (IGI draws its VPLs here)
//   std::unique_ptr<Worker> make_worker();             // one per thread; Worker::render(requests, film, stats)
//   void finish(RenderStats&);                          // adds the driver's own counts (e.g. light-path rays)
//   std::vector<int> passes(int spp);                   // optional: its own pass sizes (vcm: one sample each)
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
#include "distributed/session.h"
#include "film/checkpoint.h"
#include "film/film.h"
#include "render/render.h"
#include "render/adaptive_sampling.h"
#include "render/render_control.h"
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

namespace detail {
// The progress of a render through its passes (what a checkpoint holds besides the film): `pass` is the pass in
// progress and tile_done its finished tiles. Tiles are only checked between tiles, so at any stop every tile of
// the pass is done or not started and the film is consistent with this record.
struct PassProgress {
  size_t pass = 0;
  std::vector<uint8_t> tile_done;
};
// Checkpoint bookkeeping of run_tiles: when one is due and writing it (render/render_control.h).
class CheckpointClock {
 public:
  // Only rank 0 of a distributed render holds the film; the other ranks writing the same file would race it.
  explicit CheckpointClock(const RenderControl* control)
      : control_(control && !control->checkpoint.empty() && dist::rank() == 0 ? control : nullptr),
        last_(std::chrono::steady_clock::now()) {}
  bool enabled() const { return control_ != nullptr; }
  // A distributed checkpoint waits for every unit out on the other ranks to come back, so it is written at most
  // once a second there (every 0 would otherwise serialise the ranks).
  bool due() const {
    const double every = dist::distributed() ? std::max(control_ ? control_->checkpoint_every : 0.0, 1.0)
                                             : (control_ ? control_->checkpoint_every : 0.0);
    return control_ && std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count() >= every;
  }
  void write(Checkpoint& c) {
    c.key = control_->key;
    write_checkpoint(control_->checkpoint, c);
    last_ = std::chrono::steady_clock::now();
  }

 private:
  const RenderControl* control_;
  std::chrono::steady_clock::time_point last_;
};
}  // namespace detail

namespace detail {
// One render thread's worker, request list and counts.
template <class Worker>
struct Slot {
  std::unique_ptr<Worker> worker;
  std::vector<SampleRequest> requests;
  RenderStats stats;
};
template <class Worker>
constexpr bool kSplats = requires(Worker& w, std::span<const SampleRequest> r, Film& f, RenderStats& st,
                                  SplatBuffer& b) { w.render(r, f, st, b); };

// Renders samples [first_sample, first_sample + pass_spp) of every pixel of `tile` (of those whose `active`
// byte is set, when adaptive sampling gives one) into `film` (and `splats` for integrators that splat), in
// wavefronts of kWavefrontSamples in request order. Returns the samples.
template <class Worker>
size_t render_tile(Slot<Worker>& w, const Tile& tile, int width, int first_sample, int pass_spp, Film& film,
                   SplatBuffer* splats, const uint8_t* active = nullptr) {
  w.requests.clear();
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x = tile.x0; x < tile.x1; ++x) {
      const uint32_t pixel = uint32_t(y) * uint32_t(width) + uint32_t(x);
      if (active && !active[pixel]) continue;
      for (int s = first_sample; s < first_sample + pass_spp; ++s) w.requests.push_back({pixel, uint32_t(s)});
    }
  const std::span<const SampleRequest> all(w.requests);
  for (size_t b = 0; b < all.size(); b += kWavefrontSamples) {
    const auto chunk = all.subspan(b, std::min(kWavefrontSamples, all.size() - b));
    if constexpr (kSplats<Worker>) {
      w.worker->render(chunk, film, w.stats, *splats);  // chunks in order: the tile's splats keep theirs
    } else {
      w.worker->render(chunk, film, w.stats);
    }
  }
  return w.requests.size();
}

inline void set_counters(uint64_t out[5], const RenderStats& s) {
  const uint64_t c[5] = {s.camera_rays, s.extension_rays, s.shadow_rays, s.dropped_samples, s.samples_done};
  std::copy(c, c + 5, out);
}
inline void add_counters(RenderStats& s, const uint64_t c[5]) {
  s.camera_rays += c[0], s.extension_rays += c[1], s.shadow_rays += c[2], s.dropped_samples += c[3];
  s.samples_done += c[4];
}

// Writes a checkpoint of `film` at `at` (the film is lent to it, not copied); `splats` from `next_merge` on are
// the done tiles' unmerged splats, `stats` the counts so far.
inline void save_checkpoint(CheckpointClock& clock, const PassProgress& at, const std::vector<SplatBuffer>& splats,
                            size_t next_merge, const RenderStats& stats, Film& film) {
  Checkpoint c;
  c.pass = uint32_t(at.pass);
  c.tile_done = at.tile_done;
  for (size_t t = next_merge; t < splats.size(); ++t)
    if (at.tile_done[t]) c.pending.emplace_back(uint32_t(t), splats[t]);
  set_counters(c.counters, stats);
  std::swap(c.film, film);
  try {
    clock.write(c);
  } catch (...) {
    std::swap(c.film, film);
    throw;
  }
  std::swap(c.film, film);
}
}  // namespace detail

namespace detail {
// RenderOutput::variance of a finished film: each pixel's from its own count (adaptive sampling) or `spp`.
inline std::vector<float> pixel_variances(const RenderSettings& settings, const Film& film,
                                          const std::vector<uint32_t>& pixel_spp, int spp) {
  std::vector<float> v;
  if (!settings.pixel_variance || film.moments().empty()) return v;
  v.resize(film.pixel_count());
  for (size_t i = 0; i < v.size(); ++i) v[i] = film.mean_variance(i, pixel_spp.empty() ? uint32_t(spp) : pixel_spp[i]);
  return v;
}
}  // namespace detail

#ifdef TORTE_HAVE_MPI
}  // namespace torte
#include "render/tile_loop_mpi.h"
namespace torte {
#endif

template <class Driver>
RenderOutput run_tiles(const Scene& scene, const RenderSettings& settings, Driver& driver, ProgressSink* progress,
                       const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<detail::Tile> tiles = detail::make_tiles(settings.width, settings.height, settings.tile_size);
  std::vector<int> passes;
  if constexpr (requires { driver.passes(settings.spp); })
    passes = driver.passes(settings.spp);
  else
    passes = detail::make_passes(settings.spp);
  Film film(settings.width, settings.height);
  AdaptiveSampler adaptive(settings.width, settings.height, settings.noise_threshold,
                           std::min(settings.adaptive_min_spp, settings.spp));
  if (adaptive.enabled()) {
    // The sampler's state (which pixels still sample, how many samples each took) lives in this process only:
    // it is neither checkpointed nor sent to other ranks (the film's moments are).
    if (dist::distributed()) throw Error("noise_threshold does not work across MPI ranks yet: render without it");
    if (settings.control)
      throw Error("noise_threshold does not work with --checkpoint or --resume yet: render without one of them");
  }
  using Worker = typename decltype(driver.make_worker())::element_type;
  constexpr bool kSplats = detail::kSplats<Worker>;
  // The film's luminance moments: adaptive sampling's error estimate, and the variance layer (camera integrators).
  if (adaptive.enabled() || (settings.pixel_variance && !kSplats)) film.track_moments();
  bool time_up = false;
  using Slot = detail::Slot<Worker>;
  PerThread<Slot> slots;
  std::atomic<uint64_t> samples_done{0}, rays_done{0};
  uint64_t samples_total = uint64_t(settings.width) * settings.height * settings.spp;
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  auto cancelled = [&] { return cancel && cancel->load(std::memory_order_relaxed); };
  const bool has_images = !scene.textures.images().empty();
  auto texture_failed = [&] { return has_images && !detail::texture_failure(scene).empty(); };

  std::vector<SplatBuffer> splats(kSplats ? tiles.size() : 0);
  detail::PassProgress at;
  at.tile_done.assign(tiles.size(), 0);
  size_t next_merge = 0;  // the first tile of the pass whose splats are not merged yet
  std::mutex merge_mutex;
  // Merges the finished tiles that follow the merged ones, in tile order (`all`: also past unfinished ones, at
  // the end of a pass, when an interruption left tiles undone).
  auto merge_ready = [&](bool all) {
    for (; next_merge < splats.size() && (all || at.tile_done[next_merge]); ++next_merge) {
      if (at.tile_done[next_merge]) film.merge_splats(splats[next_merge]);
      splats[next_merge] = SplatBuffer();  // frees its memory
    }
  };

  // Checkpoints (render/render_control.h): resume restores the film and the pass record; the counters of the
  // samples done before keep the splat scale (pixels / samples done) and the summary what they would have been.
  const RenderControl* control = settings.control;
  detail::CheckpointClock clock(control);
  RenderStats before;
  if (control && !control->resume.empty() && dist::rank() == 0) {  // the other ranks get tiles from rank 0
    Checkpoint c = read_checkpoint(control->resume, control->key);
    if (c.tile_done.size() != tiles.size() || c.pass > passes.size())
      throw Error("--resume " + control->resume + ": corrupt (tiles or passes do not match its settings)");
    film = std::move(c.film);
    at.pass = c.pass;
    at.tile_done = std::move(c.tile_done);
    for (auto& [tile, buffer] : c.pending) splats[tile] = std::move(buffer);
    while (next_merge < splats.size() && at.tile_done[next_merge]) ++next_merge;  // merged before the save
    detail::add_counters(before, c.counters);
    samples_done = before.samples_done;
    rays_done = before.rays();
  }
  auto save = [&] {
    RenderStats sum = before;
    for (const Slot& w : slots) sum.add(w.stats);
    detail::save_checkpoint(clock, at, splats, next_merge, sum, film);
  };
#ifdef TORTE_HAVE_MPI
  if (dist::distributed())
    return detail::run_tiles_distributed(scene, settings, driver, progress, cancel, tiles, passes, film, at, splats,
                                         next_merge, before, clock, start);
#endif

  std::vector<size_t> todo;
  std::atomic<bool> stop_for_checkpoint{false};
  int first_sample = 0;
  for (size_t p = 0; p < at.pass; ++p) first_sample += passes[p];  // resumed in a later pass
  for (; at.pass < passes.size(); ++at.pass) {
    const int pass_spp = passes[at.pass];
    if (cancelled() || texture_failed()) break;
    if (at.pass > 0 && settings.time_limit > 0 && elapsed() >= settings.time_limit) {
      time_up = true;  // at a pass boundary: every pixel has the same samples (or adaptive sampling's share)
      break;
    }
    driver.begin_pass(first_sample, pass_spp);
    for (;;) {  // until the pass is done; a checkpoint stops it between tiles and starts the rest
      todo.clear();
      for (size_t t = 0; t < tiles.size(); ++t)
        if (!at.tile_done[t]) todo.push_back(t);
      if (todo.empty()) break;
      stop_for_checkpoint = false;
      parallel_for_blocks(size_t(0), todo.size(), 1, [&](IndexRange<size_t> range) {
        Slot& w = slots.local();
        if (!w.worker) {
          w.worker = driver.make_worker();
          w.stats.stages.enabled = settings.stage_stats;
        }
        for (size_t i = range.begin(); i != range.end(); ++i) {
          if (cancelled() || texture_failed()) return;
          if (clock.enabled() && (stop_for_checkpoint.load(std::memory_order_relaxed) || clock.due())) {
            stop_for_checkpoint = true;
            return;
          }
          const size_t t = todo[i];
          const uint64_t rays_before = w.stats.rays();
          const size_t n = detail::render_tile(w, tiles[t], settings.width, first_sample, pass_spp, film,
                                               kSplats ? &splats[t] : nullptr, adaptive.active());
          if constexpr (kSplats) {
            const std::lock_guard<std::mutex> lock(merge_mutex);
            at.tile_done[t] = 1;
            merge_ready(false);
          } else {
            at.tile_done[t] = 1;  // one byte per tile, each written by the thread rendering the tile
          }
          const uint64_t done = samples_done += n;
          const uint64_t rays = rays_done += w.stats.rays() - rays_before;
          if (progress) progress->update(done, samples_total, rays, elapsed());
        }
      }, Split::each_block);
      if (cancelled() || texture_failed() || !stop_for_checkpoint) break;
      save();
    }
    const bool pass_done = std::all_of(at.tile_done.begin(), at.tile_done.end(), [](uint8_t d) { return d != 0; });
    if (!pass_done) {
      if (clock.enabled() && cancelled() && !texture_failed()) save();  // Ctrl-C: resume continues from here
      if constexpr (kSplats) merge_ready(true);
      break;
    }
    if constexpr (kSplats) merge_ready(true);
    std::fill(at.tile_done.begin(), at.tile_done.end(), uint8_t(0));
    next_merge = 0;
    first_sample += pass_spp;
    if (adaptive.enabled()) {
      const size_t left = adaptive.end_pass(film, pass_spp);
      samples_total = samples_done + uint64_t(left) * uint64_t(settings.spp - first_sample);
      if (left == 0) {
        ++at.pass;  // every pixel converged: the remaining passes have nothing to do
        break;
      }
    }
    if (clock.due() || (clock.enabled() && at.pass + 1 == passes.size())) {
      ++at.pass;  // recorded as the next pass, none of its tiles done
      save();
      --at.pass;
    }
  }

  if (const std::string failure = detail::texture_failure(scene); !failure.empty()) throw Error(failure);
  RenderOutput out;
  out.stats = before;
  for (const Slot& w : slots) {
    out.stats.add(w.stats);
    if (w.worker) ++out.stats.stages.threads;
  }
  out.stats.stages.enabled = settings.stage_stats;
  driver.finish(out.stats);
  out.stats.interrupted = cancelled() && out.stats.samples_done < samples_total;
  out.stats.time_limited = time_up;
  out.stats.spp_reached = first_sample;
  out.pixel_spp = adaptive.pixel_spp();
  out.variance = detail::pixel_variances(settings, film, out.pixel_spp, first_sample);
  const uint64_t pixels = uint64_t(settings.width) * uint64_t(settings.height);
  out.image = film.image(kSplats && out.stats.samples_done > 0 ? float(double(pixels) / double(out.stats.samples_done))
                                                               : 1.0f);
  out.stats.render_seconds = elapsed();
  return out;
}

}  // namespace torte
