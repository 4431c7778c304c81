#include "render/integrator_mlt.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "core/primary_samples.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "render/bdpt_tracer.h"

namespace torte {

namespace {

static_assert(PrimarySamples::kLightRegion == kDimLightSubpathBase, "the light subpath's sampler dimensions");
static_assert(PrimarySamples::kSinglesRegion == kDimEmitPosition - 1, "the single dimensions (lens, emission)");
constexpr uint32_t kDimPixel = PrimarySamples::kSinglesRegion + 8;  // the pixel a chain's camera subpath starts in
constexpr uint32_t kGroupChains = 1024;  // chains advanced together: one wavefront (as tile_loop.h makes them)
constexpr uint32_t kRoundMutations = 16;  // mutations per chain between merges (and Ctrl-C / time checks)

struct PixelValue {
  uint32_t pixel;
  Rgb value;
};

// A fixed set of chains, advanced by one thread at a time: what it computes does not depend on which thread.
struct Group {
  PrimarySamples samples;
  std::vector<std::vector<PixelValue>> current, proposed;  // per chain: what its path adds to the image
  std::vector<float> current_i, proposed_i;                // ... and the luminance of that
  std::vector<Pcg32> rng;                                  // per chain: step kinds and acceptance
  std::vector<PixelValue> splats;                          // this round's weighted contributions
  double large_sum = 0;                                    // I of this round's large steps
  uint64_t large_count = 0;
  Group(uint64_t seed, uint32_t first, uint32_t n, uint32_t region)
      : samples(seed, first, n, region), current(n), proposed(n), current_i(n, 0), proposed_i(n, 0) {
    rng.reserve(n);
    for (uint32_t c = 0; c < n; ++c) rng.emplace_back(mix_bits(seed ^ 0x3c6ef372fe94f82bULL), first + c);
  }
  uint32_t size() const { return uint32_t(current.size()); }
};

struct Worker {
  Sampler sampler;
  BdptTracer tracer;
  std::vector<SampleRequest> requests;
  std::vector<SampleContribution> out;
  RenderStats stats;
  Worker(const Scene& scene, const Camera& camera, const RenderSettings& settings, const BdptSettings& bdpt)
      : sampler(settings.seed), tracer(scene, camera, settings, sampler, bdpt) {}

  // The paths of chains [0, n) of `samples` (their proposals while proposing): per chain its contributions
  // and their luminance.
  void evaluate(const PrimarySamples& samples, uint32_t n, int width, int height,
                std::vector<std::vector<PixelValue>>& lists, std::vector<float>& lum) {
    sampler.use_primary_samples(&samples);
    requests.clear();
    for (uint32_t c = 0; c < n; ++c) {
      const Vec2f u = samples.get_2d(c, kDimPixel);
      const uint32_t x = std::min(uint32_t(width) - 1, uint32_t(u.x * float(width)));
      const uint32_t y = std::min(uint32_t(height) - 1, uint32_t(u.y * float(height)));
      requests.push_back({y * uint32_t(width) + x, c});
    }
    out.clear();
    tracer.contributions(requests, width, height, stats, out);
    stats.samples_done += n;
    for (uint32_t c = 0; c < n; ++c) {
      lists[c].clear();
      lum[c] = 0;
    }
    for (const SampleContribution& s : out) {
      lists[s.request].push_back({s.pixel, s.value});
      lum[s.request] += s.value.luminance();
    }
    for (uint32_t c = 0; c < n; ++c) lum[c] = std::isfinite(lum[c]) ? std::max(lum[c], 0.0f) : 0.0f;
    sampler.use_primary_samples(nullptr);
  }
};

// One mutation of every chain of the group: propose, trace, splat both states with their expected weights,
// accept or reject.
void mutate(Worker& w, Group& g, float large_step, int width, int height) {
  const uint32_t n = g.size();
  std::vector<uint8_t> large(n);
  for (uint32_t c = 0; c < n; ++c) {
    large[c] = g.rng[c].next_float() < large_step;
    g.samples.propose(c, large[c]);
  }
  w.evaluate(g.samples, n, width, height, g.proposed, g.proposed_i);
  for (uint32_t c = 0; c < n; ++c) {
    const float ix = g.current_i[c], iy = g.proposed_i[c];
    const float a = ix > 0 ? std::min(1.0f, iy / ix) : 1.0f;
    if (iy > 0)
      for (const PixelValue& v : g.proposed[c]) g.splats.push_back({v.pixel, v.value * (a / iy)});
    if (ix > 0 && a < 1)
      for (const PixelValue& v : g.current[c]) g.splats.push_back({v.pixel, v.value * ((1 - a) / ix)});
    if (large[c]) {
      g.large_sum += iy;
      ++g.large_count;
    }
    if (g.rng[c].next_float() < a) {
      g.samples.accept(c);
      std::swap(g.current[c], g.proposed[c]);
      g.current_i[c] = iy;
    } else {
      g.samples.reject(c);
    }
  }
}

}  // namespace

RenderOutput render_mlt(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                        ProgressSink* progress, const std::atomic<bool>* cancel) {
  if (const std::string why = bdpt_problem(scene, camera); !why.empty()) throw Error("integrator 'mlt': " + why);
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  const auto cancelled = [&] { return cancel && cancel->load(std::memory_order_relaxed); };
  const MltSettings mlt = MltSettings::from(settings);
  const BdptSettings bdpt{mlt.max_depth, mlt.rr_depth};
  const int width = settings.width, height = settings.height;
  const uint64_t pixels = uint64_t(width) * uint64_t(height);
  const uint64_t mutations_asked = pixels * uint64_t(settings.spp);
  const uint32_t chains = uint32_t(std::clamp<uint64_t>(
      mlt.chains > 0 ? uint64_t(mlt.chains) : std::min<uint64_t>(4096, mutations_asked / 64), 1, mutations_asked));
  const uint64_t per_chain = mutations_asked / chains;
  const uint64_t bootstrap = std::clamp<uint64_t>(mutations_asked / 8, chains, uint64_t(1) << 18);
  const uint32_t region = 8 + uint32_t(mlt.max_depth + 3) * kDimsPerBounce;
  const uint64_t total = bootstrap + chains + chains * per_chain;

  PerThread<std::unique_ptr<Worker>> workers;
  const auto worker = [&]() -> Worker& {
    auto& w = workers.local();
    if (!w) w = std::make_unique<Worker>(scene, camera, settings, bdpt);
    return *w;
  };
  uint64_t done = 0;
  const auto report = [&] {
    if (!progress) return;
    uint64_t rays = 0;
    for (const auto& w : workers)
      if (w) rays += w->stats.rays();
    progress->update(done, total, rays, elapsed());
  };

  // Bootstrap: fresh vectors, their luminance, in blocks of one wavefront.
  std::vector<float> boot_i(bootstrap, 0.0f);
  const uint64_t boot_blocks = (bootstrap + kGroupChains - 1) / kGroupChains;
  parallel_for(uint64_t(0), boot_blocks, [&](uint64_t b) {
    if (cancelled()) return;
    const uint64_t first = b * kGroupChains;
    const uint32_t n = uint32_t(std::min<uint64_t>(kGroupChains, bootstrap - first));
    PrimarySamples samples(settings.seed, 0, n, region);
    for (uint32_t c = 0; c < n; ++c) samples.start_at(c, samples.bootstrap_key(first + c));
    std::vector<std::vector<PixelValue>> lists(n);
    std::vector<float> lum(n);
    worker().evaluate(samples, n, width, height, lists, lum);
    std::copy(lum.begin(), lum.end(), boot_i.begin() + ptrdiff_t(first));
  });
  done += bootstrap;
  report();
  double b_sum = 0;
  for (const float i : boot_i) b_sum += i;
  uint64_t b_count = bootstrap;

  RenderOutput out;
  out.image.width = width;
  out.image.height = height;
  out.image.pixels.assign(pixels, Rgb(0));
  std::vector<double> acc(pixels * 3, 0.0);
  uint64_t mutations_done = 0;
  bool time_up = false;
  if (b_sum > 0 && !cancelled()) {
    // Chains start at bootstrap samples drawn in proportion to I (stratified over the chains).
    const Distribution1D pick(boot_i);
    std::vector<Group> groups;
    for (uint32_t first = 0; first < chains; first += kGroupChains)
      groups.emplace_back(settings.seed, first, std::min(kGroupChains, chains - first), region);
    parallel_for(size_t(0), groups.size(), [&](size_t gi) {
      Group& g = groups[gi];
      const uint32_t first = uint32_t(gi) * kGroupChains;
      for (uint32_t c = 0; c < g.size(); ++c) {
        const int k = pick.sample_discrete((float(first + c) + 0.5f) / float(chains));
        g.samples.start_at(c, g.samples.bootstrap_key(uint64_t(k)));
      }
      worker().evaluate(g.samples, g.size(), width, height, g.current, g.current_i);
    });
    done += chains;
    report();
    for (uint64_t m = 0; m < per_chain;) {
      if (cancelled()) break;
      if (m > 0 && settings.time_limit > 0 && elapsed() >= settings.time_limit) {
        time_up = true;
        break;
      }
      const uint64_t round = std::min<uint64_t>(kRoundMutations, per_chain - m);
      parallel_for(size_t(0), groups.size(), [&](size_t gi) {
        Worker& w = worker();
        for (uint64_t r = 0; r < round; ++r) mutate(w, groups[gi], mlt.large_step, width, height);
      });
      for (Group& g : groups) {  // in group order: the sums do not depend on threads
        for (const PixelValue& v : g.splats) {
          double* p = &acc[size_t(v.pixel) * 3];
          p[0] += v.value.r;
          p[1] += v.value.g;
          p[2] += v.value.b;
        }
        g.splats.clear();
        b_sum += g.large_sum;
        b_count += g.large_count;
        g.large_sum = 0;
        g.large_count = 0;
      }
      m += round;
      mutations_done += round * chains;
      done += round * chains;
      report();
    }
  }
  if (mutations_done > 0) {
    // Each mutation adds splats of total luminance 1: scaled so the image's total luminance is pixels * E[I].
    const double scale = double(pixels) * (b_sum / double(b_count)) / double(mutations_done);
    for (size_t p = 0; p < pixels; ++p)
      out.image.pixels[p] = Rgb(float(acc[p * 3] * scale), float(acc[p * 3 + 1] * scale), float(acc[p * 3 + 2] * scale));
  }
  for (const auto& w : workers)
    if (w) {
      out.stats.add(w->stats);
      ++out.stats.stages.threads;
    }
  out.stats.stages.enabled = settings.stage_stats;
  out.stats.render_seconds = elapsed();
  out.stats.interrupted = cancelled() && mutations_done < chains * per_chain;
  out.stats.time_limited = time_up;
  out.stats.spp_reached = int(mutations_done / pixels);
  return out;
}

}  // namespace torte
