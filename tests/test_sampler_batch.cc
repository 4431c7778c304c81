// Sampler::get_batch against the one-at-a-time get_2d / get_1d, bit for bit, on every Highway target the kernel
// (simd/sampler_batch.h) is compiled for, and with Metropolis chains' primary samples in place.
#include <catch2/catch.hpp>

#include <bit>
#include <cstdint>
#include <vector>

#include "core/primary_samples.h"
#include "core/rng.h"
#include "core/sampler.h"
#include "hwy_targets.h"
#include "simd/sampler_batch.h"

namespace torte {
namespace {

struct Requests {
  std::vector<uint32_t> pixel, sample, dim;
};

// Random requests, with the corners of each range: sample indices with the top bit set (unsigned conversion),
// the last dimensions, pixel 0 and the largest.
Requests make_requests(size_t n, uint64_t seed) {
  Pcg32 rng(seed);
  Requests r;
  for (size_t k = 0; k < n; ++k) {
    const uint32_t bits = rng.next_u32();
    r.pixel.push_back(k % 7 == 0 ? 0u : k % 7 == 1 ? 0xffffffffu : bits % 1000000u);
    r.sample.push_back(k % 5 == 0 ? 0x80000000u + uint32_t(k) : k % 5 == 1 ? 0xffffffffu : uint32_t(k % 4096));
    r.dim.push_back(k % 3 == 0 ? 0xffffffu - uint32_t(k) : uint32_t(rng.next_u32() % 4096));
  }
  return r;
}

TEST_CASE("sampler batch: get_batch gives get_2d's bits on every target", "[sampler]") {
  for (const uint64_t sampler_seed : {uint64_t(0), uint64_t(12345)}) {
    const Sampler sampler(sampler_seed);
    // Counts around the vector widths (1, 4, 8, 16 lanes) exercise the remainder path.
    for (const size_t n : {size_t(1), size_t(3), size_t(16), size_t(17), size_t(1000)}) {
      const Requests r = make_requests(n, n + sampler_seed);
      test::for_each_hwy_target(&sampler_batch_target_name, [&](const std::string&) {
        std::vector<float> x(n, -1), y(n, -1), x1(n, -1);
        std::vector<uint32_t> scratch(3 * n);
        sampler.get_batch(n, r.pixel.data(), r.sample.data(), r.dim.data(), x.data(), y.data(), scratch.data());
        sampler.get_batch(n, r.pixel.data(), r.sample.data(), r.dim.data(), x1.data(), nullptr, scratch.data());
        for (size_t k = 0; k < n; ++k) {
          const Vec2f u = sampler.get_2d(r.pixel[k], r.sample[k], r.dim[k]);
          INFO("n " << n << " request " << k << ": pixel " << r.pixel[k] << " sample " << r.sample[k] << " dim "
                    << r.dim[k]);
          REQUIRE(std::bit_cast<uint32_t>(x[k]) == std::bit_cast<uint32_t>(u.x));
          REQUIRE(std::bit_cast<uint32_t>(y[k]) == std::bit_cast<uint32_t>(u.y));
          REQUIRE(std::bit_cast<uint32_t>(x1[k]) ==
                  std::bit_cast<uint32_t>(sampler.get_1d(r.pixel[k], r.sample[k], r.dim[k])));
          REQUIRE(x[k] >= 0);
          REQUIRE(x[k] < 1);
        }
      });
    }
  }
}

TEST_CASE("sampler batch: Metropolis chains' primary samples pass through get_batch", "[sampler]") {
  PrimarySamples primary(4, 0, 4, 16);
  for (uint32_t c = 0; c < 4; ++c) primary.start_at(c, primary.bootstrap_key(c));
  Sampler sampler(3);
  sampler.use_primary_samples(&primary);
  const Requests r = make_requests(40, 9);
  std::vector<uint32_t> sample(40);
  for (size_t k = 0; k < 40; ++k) sample[k] = uint32_t(k % 4);  // chain indices
  std::vector<float> x(40), y(40);
  std::vector<uint32_t> scratch(120);
  std::vector<uint32_t> dim(40);
  for (size_t k = 0; k < 40; ++k) dim[k] = uint32_t(k % 11);
  sampler.get_batch(40, r.pixel.data(), sample.data(), dim.data(), x.data(), y.data(), scratch.data());
  for (size_t k = 0; k < 40; ++k) {
    const Vec2f u = sampler.get_2d(r.pixel[k], sample[k], dim[k]);
    CHECK(x[k] == u.x);
    CHECK(y[k] == u.y);
  }
}

}  // namespace
}  // namespace torte
