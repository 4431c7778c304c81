// The feature-guided denoiser (film/denoise.h) on synthetic images whose noise-free answer is known: noise
// falls, texture detail in the albedo and edges between surfaces survive, means are kept, bad input is refused.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <tbb/global_control.h>

#include "core/error.h"
#include "core/rng.h"
#include "core/vec.h"
#include "film/denoise.h"

using namespace torte;

namespace {

constexpr int kW = 64, kH = 64;

struct Synthetic {
  Image noisy;
  std::vector<Rgb> truth;
};

// Lighting that varies smoothly, times an albedo checker of 8-pixel squares, plus noise of relative size
// `noise`; normals and depth of one plane unless `split`, which turns the right half to face another way and
// makes it four times brighter.
Synthetic make(float noise, bool split = false) {
  Synthetic s;
  s.noisy = Image(kW, kH);
  s.truth.resize(size_t(kW) * kH);
  ImageLayer albedo{"albedo", {"R", "G", "B"}, {}}, normal{"normal", {"X", "Y", "Z"}, {}}, depth{"depth", {"Z"}, {}};
  Pcg32 rng(7);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool right = split && x >= kW / 2;
      const float a = split ? 0.5f : (((x / 8) + (y / 8)) % 2 ? 0.8f : 0.2f);
      const float light = (right ? 4.0f : 1.0f) * (0.5f + 0.3f * float(x) / kW + 0.2f * float(y) / kH);
      const size_t i = size_t(y) * kW + size_t(x);
      s.truth[i] = Rgb(a * light);
      // Noise like a renderer's: zero-mean, a sum of uniforms (close to Gaussian).
      const float n = (rng.next_float() + rng.next_float() + rng.next_float() - 1.5f) * 2 * noise;
      s.noisy.pixels[i] = Rgb(a * light * (1 + n));
      albedo.values.insert(albedo.values.end(), {a, a, a});
      const Vec3f nn = right ? Vec3f(0.7071f, 0, -0.7071f) : Vec3f(0, 0, -1);
      normal.values.insert(normal.values.end(), {nn.x, nn.y, nn.z});
      depth.values.push_back(3);
    }
  s.noisy.layers = {albedo, normal, depth};
  return s;
}

double rmse(const std::vector<Rgb>& a, const std::vector<Rgb>& b, bool (*keep)(int, int) = nullptr) {
  double sum = 0;
  size_t n = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (keep && !keep(x, y)) continue;
      const size_t i = size_t(y) * kW + size_t(x);
      const Rgb d = a[i] - b[i];
      sum += double(d.r) * d.r + double(d.g) * d.g + double(d.b) * d.b;
      n += 3;
    }
  return std::sqrt(sum / double(n));
}

// The mean of 16 samples that are each 0 or `value / q` with probability q: a renderer's noise when a rare path
// carries the light (shadow rays to a small emitter, caustics), heavy-tailed for small q; its mean is `value`.
float mc_pixel(float value, float q, Pcg32& rng) {
  float sum = 0;
  for (int k = 0; k < 16; ++k) sum += rng.next_float() < q ? value / q : 0.0f;
  return sum / 16;
}

// One plane of albedo 0.5 lit by `truth` (a kW x kH luminance), rendered by mc_pixel with probability q.
Synthetic make_mc(const std::vector<float>& truth, float q, uint64_t seed) {
  Synthetic s;
  s.noisy = Image(kW, kH);
  s.truth.resize(truth.size());
  ImageLayer albedo{"albedo", {"R", "G", "B"}, {}}, normal{"normal", {"X", "Y", "Z"}, {}}, depth{"depth", {"Z"}, {}};
  Pcg32 rng(seed);
  for (size_t i = 0; i < truth.size(); ++i) {
    s.truth[i] = Rgb(0.5f * truth[i]);
    s.noisy.pixels[i] = Rgb(0.5f * mc_pixel(truth[i], q, rng));
    albedo.values.insert(albedo.values.end(), {0.5f, 0.5f, 0.5f});
    normal.values.insert(normal.values.end(), {0.0f, 0.0f, -1.0f});
    depth.values.push_back(3);
  }
  s.noisy.layers = {albedo, normal, depth};
  return s;
}

// Pixels next to an albedo checker edge.
bool near_checker_edge(int x, int y) { return x % 8 == 0 || x % 8 == 7 || y % 8 == 0 || y % 8 == 7; }

}  // namespace

TEST_CASE("denoise: noise falls at least 3x, also at the texture's edges, and the mean is kept", "[denoise]") {
  const Synthetic s = make(0.3f);
  const Image out = denoise(s.noisy);
  const double before = rmse(s.noisy.pixels, s.truth), after = rmse(out.pixels, s.truth);
  INFO("rmse " << before << " -> " << after);
  CHECK(after < before / 3);
  const double edge_before = rmse(s.noisy.pixels, s.truth, near_checker_edge);
  const double edge_after = rmse(out.pixels, s.truth, near_checker_edge);
  INFO("at checker edges " << edge_before << " -> " << edge_after);
  CHECK(edge_after < edge_before / 3);  // texture detail is in the albedo: not blurred
  double m0 = 0, m1 = 0;
  for (size_t i = 0; i < out.pixels.size(); ++i) m0 += s.noisy.pixels[i].g, m1 += out.pixels[i].g;
  CHECK(m1 == Approx(m0).epsilon(0.01));
}

TEST_CASE("denoise: an edge between surfaces facing other ways stays sharp", "[denoise]") {
  // Little noise, so that a column's mean is known to 0.6 %: a blur across the edge (4x brighter on the right)
  // would pull the columns beside it towards each other by far more.
  const Synthetic s = make(0.05f, true);
  const Image out = denoise(s.noisy);
  for (int x : {kW / 2 - 1, kW / 2}) {
    double got = 0, want = 0;
    for (int y = 0; y < kH; ++y) got += out.at(x, y).g, want += s.truth[size_t(y) * kW + size_t(x)].g;
    INFO("column " << x);
    CHECK(got == Approx(want).epsilon(0.02));
  }
  CHECK(rmse(out.pixels, s.truth) < rmse(s.noisy.pixels, s.truth) / 3);
}

TEST_CASE("denoise: the noisy input is kept as a layer, the features too", "[denoise]") {
  const Synthetic s = make(0.1f);
  const Image out = denoise(s.noisy);
  const ImageLayer* noisy = out.layer("noisy");
  REQUIRE(noisy);
  for (size_t i = 0; i < s.noisy.pixels.size(); ++i) REQUIRE(noisy->at(i)[1] == s.noisy.pixels[i].g);
  CHECK(out.layer("albedo"));
  // Denoising the denoised image replaces its "noisy" layer rather than adding a second.
  const Image again = denoise(out);
  int count = 0;
  for (const ImageLayer& l : again.layers) count += l.name == "noisy";
  CHECK(count == 1);
}

TEST_CASE("denoise: missing or mismatched features and bad options are errors", "[denoise]") {
  Synthetic s = make(0.1f);
  Image no_albedo = s.noisy;
  no_albedo.layers.erase(no_albedo.layers.begin());
  CHECK_THROWS_WITH(denoise(no_albedo), Catch::Contains("'albedo'"));
  Image short_depth = s.noisy;
  short_depth.layers[2].values.pop_back();
  CHECK_THROWS_WITH(denoise(short_depth), Catch::Contains("'depth'"));
  CHECK_THROWS_WITH(denoise(s.noisy, {0, 5}), Catch::Contains("strength"));
  CHECK_THROWS_WITH(denoise(s.noisy, {1, 0}), Catch::Contains("iterations"));
  CHECK_THROWS_AS(denoise(Image()), Error);
}

TEST_CASE("denoise: heavy-tailed noise (rare bright samples) falls 3x and the mean is kept", "[denoise]") {
  std::vector<float> light(size_t(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) light[size_t(y) * kW + size_t(x)] = 0.5f + 0.5f * float(x + y) / (kW + kH);
  const Synthetic s = make_mc(light, 0.2f, 11);  // relative noise of a pixel: sqrt(0.8 / 3.2) = 50 %
  const Image out = denoise(s.noisy);
  const double before = rmse(s.noisy.pixels, s.truth), after = rmse(out.pixels, s.truth);
  INFO("rmse " << before << " -> " << after);
  CHECK(after < before / 3);
  double m0 = 0, m1 = 0;
  for (size_t i = 0; i < out.pixels.size(); ++i) m0 += s.truth[i].g, m1 += out.pixels[i].g;
  CHECK(m1 == Approx(m0).epsilon(0.03));  // fireflies are spread, not removed: their energy stays
}

TEST_CASE("denoise: a highlight a few pixels wide on the same surface is not blurred away", "[denoise]") {
  // A 4x4 highlight 8 times brighter than the surface around it, which no feature marks (a glossy reflection of
  // a small light): only its lighting, clearly above the noise, tells it apart. A noise estimate that took the
  // highlight's edge for noise would let the filter average it with the surface around it.
  std::vector<float> light(size_t(kW) * kH, 0.25f);
  const auto in_spot = [](int x, int y) { return x >= 30 && x < 34 && y >= 30 && y < 34; };
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (in_spot(x, y)) light[size_t(y) * kW + size_t(x)] = 2.0f;
  const Synthetic s = make_mc(light, 0.5f, 12);  // relative noise 25 %
  const Image out = denoise(s.noisy);
  double spot = 0, spot_truth = 0, ring = 0, ring_truth = 0;
  for (int y = 26; y < 38; ++y)
    for (int x = 26; x < 38; ++x) {
      const size_t i = size_t(y) * kW + size_t(x);
      (in_spot(x, y) ? spot : ring) += out.pixels[i].g;
      (in_spot(x, y) ? spot_truth : ring_truth) += s.truth[i].g;
    }
  INFO("spot " << spot << " of " << spot_truth << ", ring " << ring << " of " << ring_truth);
  CHECK(spot == Approx(spot_truth).epsilon(0.1));  // (16 pixels at 25 %: the raw sum is within 6 % at 1 sigma)
  CHECK(ring == Approx(ring_truth).epsilon(0.1));
}

TEST_CASE("denoise: bitwise the same on one thread and on several", "[denoise]") {
  const Synthetic s = make(0.3f);
  Image one, many;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = denoise(s.noisy);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 4);
    many = denoise(s.noisy);
  }
  REQUIRE(one.pixels.size() == many.pixels.size());
  CHECK(std::memcmp(one.pixels.data(), many.pixels.data(), one.pixels.size() * sizeof(Rgb)) == 0);
}

TEST_CASE("denoise: one-pixel glints whose samples agree are kept when the render's variance says so", "[denoise]") {
  // Single pixels 8 times brighter than the surface, every 8 pixels (bump-mapped metal reflecting a light): their
  // 16 samples all carry the glint (q = 1: no noise), the surface's are heavy-tailed (q = 0.5). Their spatial
  // neighbours cannot tell a glint from a firefly; the per-pixel variance of the mean (the "variance" layer
  // torte.render writes with denoise = true) can.
  std::vector<float> light(size_t(kW) * kH, 0.25f);
  const auto glint = [](int x, int y) { return x % 8 == 4 && y % 8 == 4; };
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (glint(x, y)) light[size_t(y) * kW + size_t(x)] = 2.0f;
  Synthetic s = make_mc(light, 0.5f, 13);
  Pcg32 rng(14);
  ImageLayer variance{"variance", {"Y"}, {}};
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const size_t i = size_t(y) * kW + size_t(x);
      if (glint(x, y)) {
        s.noisy.pixels[i] = s.truth[i];
        variance.values.push_back(0);
      } else {
        // The mean of 16 samples of 0 or 2 m with probability 1/2 has variance m^2 / 16 (m: the mean).
        const float m = s.truth[i].g;
        variance.values.push_back(m * m / 16);
      }
    }
  const auto glint_sum = [&](const Image& img) {
    double sum = 0, truth = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        if (glint(x, y)) sum += img.pixels[size_t(y) * kW + size_t(x)].g, truth += s.truth[size_t(y) * kW + size_t(x)].g;
    return sum / truth;
  };
  const Image without = denoise(s.noisy);
  s.noisy.layers.push_back(variance);
  const Image with = denoise(s.noisy);
  INFO("glints keep " << glint_sum(with) << " of their light with the variance layer, " << glint_sum(without)
                      << " without");
  CHECK(glint_sum(with) == Approx(1).epsilon(0.1));
  CHECK(glint_sum(without) < 0.8);  // what the layer changes: the median guide took them for fireflies
  const double before = rmse(s.noisy.pixels, s.truth), after = rmse(with.pixels, s.truth);
  INFO("rmse " << before << " -> " << after);
  CHECK(after < before / 2);  // the surface around them is still denoised
  s.noisy.layers.back().values.pop_back();
  CHECK_THROWS_AS(denoise(s.noisy), Error);  // a variance layer of the wrong size
}

TEST_CASE("denoise: a diffuse surface is filtered across normals that differ, a glossy one is not", "[denoise]") {
  // The smooth lighting of make() on a surface whose normal tilts by a random 10 degrees from pixel to pixel (a
  // normal-mapped plaster wall): diffuse lighting barely changes with it, but as a glossy surface (or without the
  // layer) almost every neighbour counts as another surface.
  Synthetic s = make(0.3f);
  ImageLayer& normal = s.noisy.layers[1];
  Pcg32 rng(11);
  for (size_t i = 0; i < size_t(kW) * kH; ++i) {
    const float phi = 2 * kPi * rng.next_float(), t = std::sin(10 * kPi / 180);
    const Vec3f nn = normalize(Vec3f(t * std::cos(phi), t * std::sin(phi), -1));
    normal.values[3 * i] = nn.x, normal.values[3 * i + 1] = nn.y, normal.values[3 * i + 2] = nn.z;
  }
  const auto with_gloss = [&](float gloss) {
    Image img = s.noisy;
    img.layers.push_back({"glossiness", {"Y"}, std::vector<float>(size_t(kW) * kH, gloss)});
    return rmse(denoise(img).pixels, s.truth);
  };
  const double noisy = rmse(s.noisy.pixels, s.truth), none = rmse(denoise(s.noisy).pixels, s.truth);
  const double diffuse = with_gloss(0.9f), glossy = with_gloss(500);
  INFO("rmse noisy " << noisy << ", no layer " << none << ", diffuse " << diffuse << ", glossy " << glossy);
  CHECK(diffuse < noisy / 3);
  CHECK(diffuse < none / 1.5);
  CHECK(glossy == none);  // the cap: as strict as without the layer

  Image bad = s.noisy;
  bad.layers.push_back({"glossiness", {"Y"}, std::vector<float>(5, 1.0f)});
  CHECK_THROWS_WITH(denoise(bad), Catch::Contains("'glossiness'"));
}

TEST_CASE("denoise: pixels that see an emitter are its emission plus the nearby surfaces' lighting", "[denoise]") {
  // A 48 x 48 emitter (radiance 2, albedo 0.2) on the plane of make(): its pixels carry noise of 10 % (a render's
  // coverage of small emitters), its "emission" layer is exact. Up to 16 pixels from the nearest surface a pixel is
  // rebuilt as the emission plus the surfaces' lighting times its albedo; deeper inside it keeps its value.
  Synthetic s = make(0.1f);
  ImageLayer emission{"emission", {"R", "G", "B"}, std::vector<float>(3 * size_t(kW) * kH, 0.0f)};
  ImageLayer* albedo = nullptr;
  for (ImageLayer& l : s.noisy.layers)
    if (l.name == "albedo") albedo = &l;
  REQUIRE(albedo);
  Pcg32 rng(11);
  const auto inside = [](int x, int y) { return x >= 8 && x < 56 && y >= 8 && y < 56; };
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (!inside(x, y)) continue;
      const size_t i = size_t(y) * kW + size_t(x);
      const float light = 0.5f + 0.3f * float(x) / kW + 0.2f * float(y) / kH;  // as make()
      s.truth[i] = Rgb(2 + 0.2f * light);
      s.noisy.pixels[i] = s.truth[i] * (1 + 0.2f * (rng.next_float() - 0.5f));
      for (int c = 0; c < 3; ++c) emission.values[3 * i + size_t(c)] = 2, albedo->values[3 * i + size_t(c)] = 0.2f;
    }
  s.noisy.layers.push_back(emission);
  const Image out = denoise(s.noisy);
  double worst_rebuilt = 0, se_before = 0, se_after = 0;
  int kept = 0, deep = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (!inside(x, y)) continue;
      const size_t i = size_t(y) * kW + size_t(x);
      const int reach = std::min(std::min(x - 7, 56 - x), std::min(y - 7, 56 - y));  // to the nearest surface
      if (reach > 16) {
        ++deep;
        kept += out.pixels[i].g == s.noisy.pixels[i].g;
        continue;
      }
      worst_rebuilt = std::max(worst_rebuilt, double(std::fabs(out.pixels[i].g - s.truth[i].g)));
      se_before += std::pow(s.noisy.pixels[i].g - s.truth[i].g, 2);
      se_after += std::pow(out.pixels[i].g - s.truth[i].g, 2);
    }
  INFO("rebuilt: worst " << worst_rebuilt << ", squared error " << se_before << " -> " << se_after);
  CHECK(worst_rebuilt < 0.05);  // the lighting is taken up to 16 pixels away: 0.3 * 16 / 64 * 0.2 at most
  CHECK(se_after < se_before / 20);
  CHECK(deep > 0);
  CHECK(kept == deep);
}
