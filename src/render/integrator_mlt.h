// Integrator `mlt`: primary-sample-space Metropolis light transport (Kelemen et al. 2002) over bidirectional path
// tracing. A BDPT sample (render/bdpt_tracer.h: one camera and one light subpath and every way of joining them,
// MIS-weighted) is a deterministic function of a vector of uniform numbers, the pixel among them; Markov chains
// wander over those vectors with a density proportional to I, the luminance of everything the sample adds to
// the image, so bright and hard-to-find paths are explored around once found. Each mutation is a small step
// (every number moved by a normal offset, sigma 0.01) or, with probability `large_step`, a fresh vector; both the
// proposal and the current state are splatted with their expected weights (Veach 1997, 11.5), so rejected
// proposals are not wasted.
//
//   parameter    type   default  meaning
//   spp          int    16       mutations per pixel: the render makes width * height * spp of them
//   max_depth    int    64       largest number of scattering events on a path (as bdpt)
//   rr_depth     int    3        Russian roulette on both subpaths from this many scattering events on
//   large_step   float  0.3      probability that a mutation draws a fresh path (in (0, 1])
//   chains       int    0        Markov chains run side by side (0: width * height * spp / 64, at most 4096)
//   seed         int    0        the seed of every random number (bootstrap, mutations, acceptance)
//
// The normalisation b = E[I] comes from bootstrap samples (fresh vectors: width * height * spp / 8 of them,
// between the chain count and 2^18), refined by every large step; chains start at bootstrap samples chosen in
// proportion to I (so they start in equilibrium, without burn-in). The image's total luminance is
// width * height * b exactly: its mean brightness is as good as b, its distribution over pixels as good as the
// chains' mixing. Chains are advanced in fixed groups of up to 1024 (a wavefront each), in rounds of 16
// mutations; groups run in parallel and their splats are added in group order after every round, so the image
// is bitwise the same for a seed at any thread count. Ctrl-C and time_limit stop between rounds.
//
// Memory: per chain 16 bytes for each sampler dimension a path of max_depth can read (about 12 * max_depth +
// 80 dimensions) and its current path's contributions; per group a round's splats. Supports what bdpt supports
// (area, point and spot lights; a perspective camera placed rigidly) and refuses the rest with bdpt's errors.
#pragma once
#include <atomic>

#include "render/integrator_bdpt.h"
#include "render/render.h"

namespace torte {

struct MltSettings {
  int max_depth = 64;
  int rr_depth = 3;
  float large_step = 0.3f;
  int chains = 0;
  static MltSettings from(const RenderSettings& s) { return {s.max_depth, s.rr_depth, s.large_step, s.chains}; }
};

/// Renders with Metropolis light transport (settings already validated, camera made for their size).
/// Throws torte::Error naming the light or camera it does not support (as bdpt).
RenderOutput render_mlt(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                        ProgressSink* progress, const std::atomic<bool>* cancel);

}  // namespace torte
