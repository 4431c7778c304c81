// Primary sample space for Metropolis light transport (Kelemen et al. 2002): a group of Markov chains, each a
// vector of uniform numbers that a renderer reads through Sampler (Sampler::use_primary_samples) instead of its
// low-discrepancy points, so that one path is a deterministic function of one vector and a mutation of the vector
// is a mutation of the path. Coordinates are mutated lazily, when first read in a proposal (pbrt-v3's MLTSampler
// does the same): a small step moves each one by a normal offset of sigma per accepted move since it was last read
// (wrapped into [0, 1)), a large step draws it afresh. Every random number is a hash of (seed, chain, iteration,
// coordinate), so a chain's path does not depend on the order its coordinates are read in, nor on threads.
//
// Coordinates are addressed by the renderer's sampler dimensions, in three regions (render/shade.h,
// render/bdpt_subpath.h, render/stage_light.h): [0, 2^25) the camera path's, [2^25, 2^30) the light subpath's
// (each region's first `region_size` dimensions), and 2^30 + k for k < kSingles. Memory: 12 bytes per
// coordinate of a chain (two floats and an iteration stamp), plus the coordinates a proposal has touched.
#pragma once
#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace torte {

class PrimarySamples {
 public:
  static constexpr uint32_t kLightRegion = 1u << 25;
  static constexpr uint32_t kSinglesRegion = 1u << 30;
  static constexpr uint32_t kSingles = 16;

  /// `chains` chains whose first `first_chain` is their global number (it keys their random numbers), each
  /// with room for `region_size` dimensions per region. Chains start unset: call start_at before reading.
  PrimarySamples(uint64_t seed, uint32_t first_chain, uint32_t chains, uint32_t region_size);

  /// Sets chain c to the uniform vector keyed by `key` (a bootstrap sample's number), not in a proposal.
  void start_at(uint32_t c, uint64_t key);
  /// Begins a proposal of chain c: coordinates read until accept/reject are mutated (small step) or drawn
  /// afresh (large step). Without a proposal, reads return the chain's current state.
  void propose(uint32_t c, bool large_step);
  /// Keeps the proposal as chain c's state.
  void accept(uint32_t c);
  /// Returns chain c to its state before the proposal.
  void reject(uint32_t c);

  /// Coordinates (2 dimension, 2 dimension + 1) of chain c, mutated first if the proposal has not read them yet.
  /// Throws torte::Error for a dimension outside the regions (a path longer than the regions were sized for).
  Vec2f get_2d(uint32_t c, uint32_t dimension) const;

  /// The key of the large step chain c proposes as its `proposal`-th proposal.
  uint64_t large_step_key(uint32_t c, uint64_t proposal) const;
  /// The key of bootstrap sample k.
  uint64_t bootstrap_key(uint64_t k) const;

  static constexpr float kSigma = 0.01f;  // small-step standard deviation (pbrt-v3's default)

 private:
  struct Chain {
    // Accepted moves + 2: the clock of the coordinates' stamps. A rejected proposal does not advance it (as in
    // pbrt-v3's MLTSampler): the small steps a coordinate skipped are those of accepted moves only. Counting
    // rejections too made the steps out of a state grow the longer the chain stayed in it, so chains left
    // bright states too easily (the Cornell box's light 4 % dark at 4096 mutations per pixel).
    uint64_t iteration = 0;
    uint64_t proposals = 0;        // every proposal made: keys the proposal's random numbers
    uint64_t large_iteration = 0;  // iteration of the accepted large step that set the unread coordinates
    uint64_t large_key = 0;        // ... and its key
    uint64_t proposal_key = 0;     // key of the large step being proposed
    bool proposing = false, large = false;
  };
  struct Backup {
    uint32_t slot;
    Vec2f value;
    uint64_t stamp;
  };
  uint32_t slot_of(uint32_t dimension) const;

  uint64_t seed_hash_;
  uint32_t first_chain_, region_size_, slots_;
  std::vector<Chain> chains_;
  mutable std::vector<Vec2f> value_;      // chains x slots
  mutable std::vector<uint64_t> stamp_;   // iteration each coordinate was last brought up to date
  mutable std::vector<std::vector<Backup>> touched_;  // per chain: coordinates the proposal changed
};

}  // namespace torte
