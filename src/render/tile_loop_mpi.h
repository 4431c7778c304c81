// run_tiles across MPI ranks (included by render/tile_loop.h when built with MPI; docs/distributed.md). Rank 0
// runs the work queue (distributed/work_queue.h) on a server thread and renders units on its other threads; the
// other ranks render the batches they are sent. Units carry their tiles' sums there and back, so every pixel
// sums its samples in the order of a one-process render: the image is the same, bit for bit.
#pragma once
#include <tbb/task_arena.h>

#include <thread>

#include "distributed/session.h"
#include "distributed/work_queue.h"

namespace torte::detail {

template <class Driver>
RenderOutput run_tiles_distributed(const Scene& scene, const RenderSettings& settings, Driver& driver,
                                   ProgressSink* progress, const std::atomic<bool>* cancel,
                                   const std::vector<Tile>& tiles, const std::vector<int>& passes, Film& film,
                                   PassProgress& at, std::vector<SplatBuffer>& splats, size_t& next_merge,
                                   const RenderStats& before, CheckpointClock& clock,
                                   std::chrono::steady_clock::time_point start) {
  using Worker = typename decltype(driver.make_worker())::element_type;
  using S = Slot<Worker>;
  constexpr bool splat = kSplats<Worker>;
  PerThread<S> slots;
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  auto cancelled = [&] { return cancel && cancel->load(std::memory_order_relaxed); };
  const bool has_images = !scene.textures.images().empty();
  auto texture_failed = [&] { return has_images && !texture_failure(scene).empty(); };
  auto worker = [&]() -> S& {
    S& w = slots.local();
    if (!w.worker) {
      w.worker = driver.make_worker();
      w.stats.stages.enabled = settings.stage_stats;
    }
    return w;
  };
  std::vector<dist::TileRect> rects;
  for (const Tile& t : tiles) rects.push_back({t.x0, t.y0, t.x1, t.y1});
  std::vector<int> first(passes.size(), 0);
  for (size_t p = 1; p < passes.size(); ++p) first[p] = first[p - 1] + passes[p - 1];
  const int threads = tbb::this_task_arena::max_concurrency();
  RenderOutput out;

  if (dist::rank() != 0) {  // render what rank 0 sends, until it says the render is over
    dist::Client client(rects, film, threads);
    dist::Client::Batch b;
    size_t last_pass = size_t(-1);
    RenderStats counted;
    while (client.next(b)) {
      if (b.pass != last_pass) driver.begin_pass(b.first_sample, b.pass_spp);
      last_pass = b.pass;
      parallel_for_blocks(size_t(0), b.tiles.size(), 1, [&](IndexRange<size_t> range) {
        S& w = worker();
        for (size_t i = range.begin(); i != range.end(); ++i) {
          if (cancelled() || texture_failed()) return;
          SplatBuffer buffer;
          render_tile(w, tiles[b.tiles[i]], settings.width, b.first_sample, b.pass_spp, film, &buffer);
          client.rendered(i, splat ? &buffer : nullptr);
        }
      }, Split::each_block);
      if (const std::string failure = texture_failure(scene); !failure.empty()) throw Error(failure);
      RenderStats sum;
      for (const S& w : slots) sum.add(w.stats);
      uint64_t now[5], then[5], delta[5];
      set_counters(now, sum);
      set_counters(then, counted);
      for (int i = 0; i < 5; ++i) delta[i] = now[i] - then[i];
      client.count(delta);
      counted = sum;
    }
    RenderStats extra;
    driver.finish(extra);
    uint64_t c[5];
    set_counters(c, extra);
    client.finish(c);
    out.image = Image(settings.width, settings.height);  // black: rank 0 holds the image
    out.stats = counted;
    out.stats.render_seconds = elapsed();
    return out;
  }

  // Rank 0. The hooks run under the queue's lock.
  const uint64_t samples_total = uint64_t(settings.width) * settings.height * settings.spp;
  std::atomic<uint64_t> samples_done{before.samples_done}, rays_done{before.rays()};
  RenderStats remote;
  auto merge_ready = [&](bool all) {
    for (; next_merge < splats.size() && (all || at.tile_done[next_merge]); ++next_merge) {
      if (at.tile_done[next_merge]) film.merge_splats(splats[next_merge]);
      splats[next_merge] = SplatBuffer();
    }
  };
  auto save = [&](const PassProgress& where) {
    RenderStats sum = before;
    sum.add(remote);
    for (const S& w : slots) sum.add(w.stats);
    save_checkpoint(clock, where, splats, next_merge, sum, film);
  };
  dist::Coordinator::Hooks hooks;
  bool time_up = false;  // set between passes (the queue asks stop() before it starts the next one)
  hooks.begin_pass = [&](size_t p) { driver.begin_pass(first[p], passes[p]); };
  hooks.end_pass = [&] {
    if constexpr (splat) merge_ready(true);
    std::fill(at.tile_done.begin(), at.tile_done.end(), uint8_t(0));
    next_merge = 0;
    ++at.pass;
    if (clock.due() || (clock.enabled() && at.pass == passes.size())) save(at);
    if (settings.time_limit > 0 && at.pass < passes.size() && elapsed() >= settings.time_limit) time_up = true;
  };
  hooks.tile_done = [&](uint32_t t) {
    at.tile_done[t] = 1;
    if constexpr (splat) merge_ready(false);
  };
  hooks.splats = [&](uint32_t t, SplatBuffer&& b) { splats[t] = std::move(b); };
  hooks.stop = [&] { return time_up || cancelled() || texture_failed(); };
  hooks.checkpoint_due = [&] { return clock.due(); };
  hooks.save = [&] { save(at); };
  hooks.progress = [&](uint64_t samples, const uint64_t counters[5]) {
    add_counters(remote, counters);
    const uint64_t done = samples_done += samples;
    const uint64_t rays = rays_done += counters[0] + counters[1] + counters[2];
    if (progress) progress->update(done, samples_total, rays, elapsed());
  };
  dist::Coordinator queue(rects, passes, at.pass, at.tile_done, film, std::move(hooks));
  std::vector<uint64_t> finals;
  std::thread server([&] {
    try {
      finals = queue.serve();
    } catch (const std::exception& e) {
      dist::abort_all(e.what());
    }
  });
  try {
    parallel_for_blocks(0, threads, 1, [&](IndexRange<int>) {
      S& w = worker();
      while (const auto unit = queue.next_local()) {
        const auto [pass, t] = *unit;
        const uint64_t rays_before = w.stats.rays();
        const size_t n = render_tile(w, tiles[t], settings.width, first[pass], passes[pass], film,
                                     splat ? &splats[t] : nullptr);
        queue.local_done(t);
        const uint64_t done = samples_done += n;
        const uint64_t rays = rays_done += w.stats.rays() - rays_before;
        if (progress) progress->update(done, samples_total, rays, elapsed());
      }
    }, Split::each_block);
  } catch (const std::exception& e) {
    dist::abort_all(e.what());  // the server thread and the other ranks would wait for this one forever
  }
  server.join();
  if (at.pass < passes.size() && !time_up) {  // stopped within a pass
    if (clock.enabled() && cancelled() && !texture_failed()) save(at);
    if constexpr (splat) merge_ready(true);
  }

  if (const std::string failure = texture_failure(scene); !failure.empty()) throw Error(failure);
  out.stats = before;
  out.stats.add(remote);
  add_counters(out.stats, finals.data());
  for (const S& w : slots) {
    out.stats.add(w.stats);
    if (w.worker) ++out.stats.stages.threads;
  }
  out.stats.stages.enabled = settings.stage_stats;
  driver.finish(out.stats);
  out.stats.interrupted = cancelled() && out.stats.samples_done < samples_total;
  out.stats.time_limited = time_up;
  out.stats.spp_reached = at.pass < passes.size() ? first[at.pass] : settings.spp;
  out.stats.units = uint64_t(tiles.size()) * passes.size();
  out.stats.remote_units = queue.remote_units();
  const uint64_t pixels = uint64_t(settings.width) * uint64_t(settings.height);
  out.image = film.image(splat && out.stats.samples_done > 0 ? float(double(pixels) / double(out.stats.samples_done))
                                                              : 1.0f);
  out.variance = pixel_variances(settings, film, {}, out.stats.spp_reached);
  out.stats.render_seconds = elapsed();
  return out;
}

}  // namespace torte::detail
