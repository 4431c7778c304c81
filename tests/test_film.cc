// Film: weighted camera samples per pixel, splats at arbitrary positions, and bitwise determinism of splats
// merged from work items that ran on 1 or 2 threads.
#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "core/parallel.h"
#include "core/rng.h"
#include "film/film.h"

using namespace torte;

TEST_CASE("film: camera samples average by filter weight, splats add on top", "[film]") {
  Film film(4, 3);
  film.add_sample(5, Rgb(1, 2, 3), 1.0f);
  film.add_sample(5, Rgb(3, 2, 1), 3.0f);
  SplatBuffer b;
  CHECK(film.splat(b, {1.5f, 1.25f}, Rgb(2)));    // pixel (1, 1) = 5
  CHECK(film.splat(b, {3.99f, 2.99f}, Rgb(1)));   // pixel (3, 2) = 11
  CHECK_FALSE(film.splat(b, {4.0f, 0.0f}, Rgb(1)));  // outside
  CHECK_FALSE(film.splat(b, {-0.01f, 0.0f}, Rgb(1)));
  CHECK_FALSE(film.splat(b, {0.5f, 0.5f}, Rgb(std::numeric_limits<float>::quiet_NaN())));
  CHECK(b.size() == 2);
  {
    const Image before = film.image();
    CHECK(before.pixels[5].r == Approx((1 + 9) / 4.0f));
    CHECK(before.pixels[11] == Rgb(0));
  }
  film.merge_splats(b);
  const Image img = film.image(0.5f);
  CHECK(img.pixels[5].r == Approx((1 + 9) / 4.0f + 1.0f));
  CHECK(img.pixels[5].b == Approx((3 + 3) / 4.0f + 1.0f));
  CHECK(img.pixels[11].g == Approx(0.5f));
  CHECK(img.pixels[0] == Rgb(0));
}

namespace {

// Splats from 64 work items (each its own buffer and random stream, values spanning many magnitudes so the sum
// depends on the order), merged in item order after a parallel run on `threads` threads.
Image splat_image(int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  constexpr int kItems = 64, kW = 37, kH = 23;
  Film film(kW, kH);
  for (uint32_t p = 0; p < film.pixel_count(); p += 3) film.add_sample(p, Rgb(0.25f), 1);
  std::vector<SplatBuffer> buffers(kItems);
  torte::parallel_for(0, kItems, [&](int item) {
    Pcg32 rng(uint64_t(item) * 7919 + 1);
    for (int k = 0; k < 4000; ++k) {
      const Vec2f p{rng.next_float() * kW * 1.1f - 1, rng.next_float() * kH * 1.1f - 1};
      const float scale = std::ldexp(1.0f, int(rng.next_u32() % 40) - 20);
      film.splat(buffers[size_t(item)], p, Rgb(rng.next_float(), rng.next_float(), rng.next_float()) * scale);
    }
  });
  std::vector<const SplatBuffer*> order;
  for (const SplatBuffer& b : buffers) order.push_back(&b);
  film.merge_splats(order);
  return film.image(1.0f / 64);
}

}  // namespace

TEST_CASE("film: splats merged from work items are bitwise identical on 1 and 2 threads", "[film][determinism]") {
  const Image one = splat_image(1), two = splat_image(2), again = splat_image(2);
  REQUIRE(one.pixels.size() == two.pixels.size());
  CHECK(std::memcmp(one.pixels.data(), two.pixels.data(), one.pixels.size() * sizeof(Rgb)) == 0);
  CHECK(std::memcmp(two.pixels.data(), again.pixels.data(), two.pixels.size() * sizeof(Rgb)) == 0);
  // Not trivially equal: the splats landed (some pixels are brighter than the camera samples alone).
  int lit = 0;
  for (const Rgb& c : one.pixels) lit += c.r > 0.26f;
  CHECK(lit > int(one.pixels.size()) / 2);
}
