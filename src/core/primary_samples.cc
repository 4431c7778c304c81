#include "core/primary_samples.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/rng.h"

namespace torte {

namespace {

constexpr uint64_t hash3(uint64_t a, uint64_t b, uint64_t c) { return mix_bits(mix_bits(mix_bits(a) ^ b) ^ c); }

Vec2f uniform2(uint64_t h) {
  const auto unit = [](uint32_t x) { return std::fmin(float(x >> 8) * 0x1p-24f, 0x1.fffffep-1f); };
  return {unit(uint32_t(h)), unit(uint32_t(h >> 32))};
}

float wrap(float v) {
  v -= std::floor(v);
  return v < 1.0f ? v : 0.0f;  // -1e-9 - floor(...) rounds to 1.0f
}

}  // namespace

PrimarySamples::PrimarySamples(uint64_t seed, uint32_t first_chain, uint32_t chains, uint32_t region_size)
    : seed_hash_(mix_bits(seed ^ 0x6a09e667f3bcc909ULL)), first_chain_(first_chain), region_size_(region_size),
      slots_(2 * region_size + kSingles), chains_(chains), value_(size_t(chains) * slots_),
      stamp_(size_t(chains) * slots_, 0), touched_(chains) {}

uint64_t PrimarySamples::large_step_key(uint32_t c, uint64_t proposal) const {
  return hash3(seed_hash_, uint64_t(first_chain_ + c) << 1, proposal);
}

uint64_t PrimarySamples::bootstrap_key(uint64_t k) const { return hash3(seed_hash_, 1, k); }

void PrimarySamples::start_at(uint32_t c, uint64_t key) {
  chains_[c] = Chain{2, 0, 1, key, 0, false, false};
  std::fill_n(stamp_.begin() + ptrdiff_t(size_t(c) * slots_), slots_, uint64_t(0));
  touched_[c].clear();
}

void PrimarySamples::propose(uint32_t c, bool large_step) {
  Chain& ch = chains_[c];
  ch.proposing = true;
  ch.large = large_step;
  ++ch.proposals;
  ch.proposal_key = large_step ? large_step_key(c, ch.proposals) : 0;
  touched_[c].clear();
}

void PrimarySamples::accept(uint32_t c) {
  Chain& ch = chains_[c];
  if (ch.large) {
    ch.large_iteration = ch.iteration;
    ch.large_key = ch.proposal_key;
  }
  ch.proposing = false;
  ++ch.iteration;
  touched_[c].clear();
}

void PrimarySamples::reject(uint32_t c) {
  Chain& ch = chains_[c];
  const size_t base = size_t(c) * slots_;
  for (const Backup& b : touched_[c]) {
    value_[base + b.slot] = b.value;
    stamp_[base + b.slot] = b.stamp;
  }
  touched_[c].clear();
  ch.proposing = false;  // the clock stays: the next proposal starts again from the same state
}

uint32_t PrimarySamples::slot_of(uint32_t d) const {
  if (d < kLightRegion) {
    if (d < region_size_) return d;
  } else if (d < kSinglesRegion) {
    if (d - kLightRegion < region_size_) return region_size_ + (d - kLightRegion);
  } else if (d - kSinglesRegion < kSingles) {
    return 2 * region_size_ + (d - kSinglesRegion);
  }
  throw Error("internal: sampler dimension " + std::to_string(d) + " lies outside the Metropolis sample space (" +
              std::to_string(region_size_) + " dimensions per region)");
}

Vec2f PrimarySamples::get_2d(uint32_t c, uint32_t dimension) const {
  const uint32_t slot = slot_of(dimension);
  const Chain& ch = chains_[c];
  const size_t i = size_t(c) * slots_ + slot;
  Vec2f& v = value_[i];
  uint64_t& stamp = stamp_[i];
  if (stamp < ch.large_iteration) {  // unread since the last accepted large step: take that step's value
    v = uniform2(hash3(ch.large_key, slot, 0));
    stamp = ch.large_iteration;
  }
  if (ch.proposing && stamp < ch.iteration) {
    touched_[c].push_back({slot, v, stamp});
    if (ch.large) {
      v = uniform2(hash3(ch.proposal_key, slot, 0));
    } else {
      // The small steps of every iteration since the coordinate was last read, as one normal step (Box-Muller).
      const Vec2f u = uniform2(hash3(seed_hash_ ^ (uint64_t(first_chain_ + c) << 20), ch.proposals, slot));
      const float r = kSigma * std::sqrt(float(ch.iteration - stamp)) * std::sqrt(-2 * std::log(1 - u.x));
      const float phi = 6.28318530718f * u.y;
      v = {wrap(v.x + r * std::cos(phi)), wrap(v.y + r * std::sin(phi))};
    }
    stamp = ch.iteration;
  }
  return v;
}

}  // namespace torte
