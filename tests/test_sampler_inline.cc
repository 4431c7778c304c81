// The inline Sampler::get_2d / get_1d (sampler.h: table shortcuts and paired bit reversals) against the plain
// composition of sobol_dim0/1 and owen_scramble, bit for bit, over random and edge-case inputs.
#include <catch2/catch.hpp>

#include <cstring>

#include "core/rng.h"
#include "core/sampler.h"

using namespace torte;

namespace {
uint32_t bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}
}  // namespace

TEST_CASE("Sampler::get_2d equals its reference composition bit for bit", "[sampler]") {
  const uint32_t edges[] = {0u, 1u, 2u, 255u, 256u, 65535u, 65536u, 0x7fffffffu, 0x80000000u, 0xffffffffu};
  for (uint64_t seed : {uint64_t(0), uint64_t(1), uint64_t(0xdeadbeefcafeULL)}) {
    const Sampler sampler(seed);
    uint64_t state = mix_bits(seed + 17);
    for (int n = 0; n < 20000; ++n) {
      state = mix_bits(state + 0x9e3779b97f4a7c15ULL);
      uint32_t px = uint32_t(state), si = uint32_t(state >> 32), dim = uint32_t(mix_bits(state) % 100000);
      if (n < 1000) px = edges[n % 10], si = edges[(n / 10) % 10], dim = edges[(n / 100) % 10];
      const Vec2f fast = sampler.get_2d(px, si, dim), ref = sampler.get_2d_reference(px, si, dim);
      REQUIRE(bits(fast.x) == bits(ref.x));
      REQUIRE(bits(fast.y) == bits(ref.y));
      REQUIRE(bits(sampler.get_1d(px, si, dim)) == bits(ref.x));
    }
  }
}
