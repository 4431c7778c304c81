// How the AOV pass (render/aov_pass.h) samples a pixel: every part of the pixel for any sample count, more samples
// where the pixel's samples disagree (outlines), emitters' outlines measured wherever a neighbour saw otherwise,
// and the albedo from several BSDF samples. Against converged references of the same pass (1,024 samples).
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "material/coated_diffuse.h"
#include "render/aov_pass.h"
#include "scene_helpers.h"

using namespace torte;
using namespace torte::test;

namespace {

constexpr int kSize = 33;

// A unit sphere at the origin under a uniform sky of 0.3, seen from (0, 0, -5); emitting `emission` if not black.
std::shared_ptr<const Scene> sphere_scene(std::shared_ptr<MaterialDesc> material, Rgb emission = Rgb(0)) {
  SceneBuilder b;
  ShapeDesc sphere = sphere_shape(1, Transform(), std::move(material));
  sphere.emission = emission;
  b.add_shape(sphere);
  b.add_light(uniform_sky(Rgb(0.3f)));
  return b.flatten();
}

ImageLayer layer_of(const Scene& scene, Aov aov, int samples, uint64_t seed = 0) {
  RenderSettings s;
  s.width = s.height = kSize;
  s.seed = seed;
  auto layers = render_aovs(scene, Camera(camera_at({0, 0, -5}, {0, 0, 0}, 30), kSize, kSize), s, {aov}, samples);
  REQUIRE(layers.size() == 1);
  return std::move(layers[0]);
}

// Pixels on the sphere's outline: their converged albedo lies between the sphere's and the sky's.
std::vector<size_t> outline(const ImageLayer& reference_albedo, float inside, float outside) {
  std::vector<size_t> px;
  for (size_t i = 0; i < size_t(kSize * kSize); ++i) {
    const float a = reference_albedo.at(i)[1];
    if (std::fabs(a - inside) > 0.01f && std::fabs(a - outside) > 0.01f) px.push_back(i);
  }
  return px;
}

}  // namespace

TEST_CASE("aov sampling: a sample count that is not a square still covers the whole pixel", "[aov]") {
  // With 8 samples a 3 x 3 grid used to be filled row by row and its last row never sampled: the sphere's upper
  // outline came out with too little sphere in it and its lower outline with too much. Averaged over seeds and
  // outline pixels, the difference between the two halves' errors must be noise.
  const auto scene = sphere_scene(matte(0.6f));
  const ImageLayer ref = layer_of(*scene, Aov::Albedo, 1024);
  const auto px = outline(ref, 0.6f, 0.3f);
  REQUIRE(px.size() > 60);
  constexpr int kSeeds = 8;
  double upper = 0, lower = 0;
  int n_upper = 0, n_lower = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const ImageLayer l = layer_of(*scene, Aov::Albedo, 8, uint64_t(seed));
    for (const size_t i : px) {
      const double err = l.at(i)[1] - ref.at(i)[1];
      if (int(i) / kSize < kSize / 2) upper += err, ++n_upper;
      else if (int(i) / kSize > kSize / 2) lower += err, ++n_lower;
    }
  }
  const double gap = std::fabs(upper / n_upper - lower / n_lower);
  CHECK(gap < 0.004);
}

TEST_CASE("aov sampling: outline pixels take more samples", "[aov]") {
  // The features of a pixel whose samples disagree are a blend its few samples estimate poorly; such pixels take
  // four times their samples again (16 + 64, on a grid twice as fine), which is what the error here shows.
  const auto scene = sphere_scene(matte(0.6f));
  const ImageLayer ref = layer_of(*scene, Aov::Albedo, 1024);
  const auto px = outline(ref, 0.6f, 0.3f);
  double se = 0;
  int n = 0;
  for (int seed = 0; seed < 4; ++seed) {
    const ImageLayer l = layer_of(*scene, Aov::Albedo, 16, uint64_t(seed));
    for (const size_t i : px) se += std::pow(l.at(i)[1] - ref.at(i)[1], 2), ++n;
  }
  // Contrast 0.3: 16 stratified samples alone leave an RMS coverage error near 0.05, i.e. 0.015 here.
  CHECK(std::sqrt(se / n) < 0.0105);
}

TEST_CASE("aov sampling: an emitter's outline is measured wherever a neighbour saw otherwise", "[aov]") {
  // A pixel that an emitter covers by a few percent is often missed by all of its 16 samples; when a neighbour
  // saw part of the emitter, the pixel's emission is measured with the outline's fine grid too.
  const auto scene = sphere_scene(matte(0.5f), Rgb(4));
  for (int seed = 0; seed < 4; ++seed) {
    const ImageLayer e = layer_of(*scene, Aov::Emission, 16, uint64_t(seed));
    const ImageLayer ref = layer_of(*scene, Aov::Emission, 1024, uint64_t(seed));
    double worst = 0;
    for (size_t i = 0; i < size_t(kSize * kSize); ++i)
      worst = std::max(worst, double(std::fabs(e.at(i)[0] - ref.at(i)[0])));
    INFO("seed " << seed);
    CHECK(worst < 0.1);  // of a radiance of 4
  }
}

TEST_CASE("aov sampling: the albedo averages several BSDF samples", "[aov]") {
  // Smooth plastic: one BSDF sample picks the coating's mirror or the diffuse base, so one sample's weight varies
  // a lot; the pass averages four. Compare the spread of the centre pixel's albedo (one camera sample, many
  // seeds) with that of single sample weights of the same BSDF seen head-on.
  auto plastic = std::make_shared<MaterialDesc>();
  plastic->type = MaterialType::CoatedDiffuse;
  plastic->color.value = Rgb(0.5f);
  plastic->eta.value = 1.5f;
  const auto scene = sphere_scene(plastic);
  const CoatedDiffuseBsdf bsdf(Rgb(0.5f), 1.5f, MicrofacetDistribution::ggx(0));
  Pcg32 rng(7, 1);
  double s1 = 0, s2 = 0;
  constexpr int kDraws = 200000;
  for (int k = 0; k < kDraws; ++k) {
    BsdfSample b;
    const float uc = rng.next_float();
    const Vec2f u{rng.next_float(), rng.next_float()};
    const double w = bsdf.sample({0, 0, 1}, uc, u, &b) && b.pdf > 0 ? b.weight().g : 0.0;
    s1 += w, s2 += w * w;
  }
  const double mean1 = s1 / kDraws, var1 = s2 / kDraws - mean1 * mean1;
  REQUIRE(var1 > 1e-3);
  const size_t centre = size_t(kSize / 2) * kSize + kSize / 2;
  constexpr int kSeeds = 400;
  double a1 = 0, a2 = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const double a = layer_of(*scene, Aov::Albedo, 1, uint64_t(seed)).at(centre)[1];
    a1 += a, a2 += a * a;
  }
  const double mean = a1 / kSeeds, var = a2 / kSeeds - mean * mean;
  CHECK(mean == Approx(mean1).margin(4 * std::sqrt(var / kSeeds) + 1e-3));  // the same albedo
  CHECK(var < 0.4 * var1);   // four samples: a quarter of the variance
  CHECK(var > 0.12 * var1);
}
