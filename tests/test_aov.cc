// The AOV pass (render/aov_pass.h): first-hit features against analytic values, specular chains, misses, layer
// names, and thread determinism.
#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>

#include "render/aov_pass.h"
#include "scene_helpers.h"

using namespace torte;
using namespace torte::test;

namespace {

constexpr int kSize = 33;  // odd: the centre pixel looks straight at the sphere's nearest point

// A unit sphere of `material` at the origin under a uniform sky of 0.3, seen from (0, 0, -5).
std::shared_ptr<const Scene> sphere_scene(std::shared_ptr<MaterialDesc> material) {
  SceneBuilder b;
  b.add_shape(sphere_shape(1, Transform(), std::move(material)));
  b.add_light(uniform_sky(Rgb(0.3f)));
  return b.flatten();
}

RenderSettings aov_settings() {
  RenderSettings s;
  s.width = s.height = kSize;
  return s;
}

std::vector<ImageLayer> aovs_of(const Scene& scene, int samples = 8, uint64_t seed = 0) {
  RenderSettings s = aov_settings();
  s.seed = seed;
  return render_aovs(scene, Camera(camera_at({0, 0, -5}, {0, 0, 0}, 30), s.width, s.height), s,
                     {Aov::Albedo, Aov::Normal, Aov::Depth, Aov::Position, Aov::MaterialId, Aov::Emission}, samples);
}

const ImageLayer& find(const std::vector<ImageLayer>& layers, const std::string& name) {
  for (const ImageLayer& l : layers)
    if (l.name == name) return l;
  FAIL("no layer " << name);
  return layers.front();
}

}  // namespace

TEST_CASE("aov: names, channels and the layers asked for, each once, in the order asked", "[aov]") {
  const auto scene = sphere_scene(matte(0.6f));
  RenderSettings s = aov_settings();
  const auto layers = render_aovs(*scene, Camera(camera_at({0, 0, -5}, {0, 0, 0}, 30), kSize, kSize), s,
                                  {Aov::Depth, Aov::Albedo, Aov::Depth}, 2);
  REQUIRE(layers.size() == 2);
  CHECK(layers[0].name == "depth");
  CHECK(layers[0].channels == std::vector<std::string>{"Z"});
  CHECK(layers[1].name == "albedo");
  CHECK(layers[1].channels == std::vector<std::string>{"R", "G", "B"});
  CHECK(layers[1].values.size() == size_t(3 * kSize * kSize));
  Aov a;
  CHECK(parse_aov("material_id", a));
  CHECK(a == Aov::MaterialId);
  CHECK_FALSE(parse_aov("albedos", a));
}

TEST_CASE("aov: a Lambert sphere's albedo, normal, depth and position at its centre; the sky around it", "[aov]") {
  const auto scene = sphere_scene(matte(0.6f));
  const auto layers = aovs_of(*scene);
  const size_t centre = size_t(kSize / 2) * kSize + kSize / 2, corner = 0;
  const float* al = find(layers, "albedo").at(centre);
  CHECK(al[0] == Approx(0.6f).margin(1e-5));  // cosine-sampled Lambert: every sample's weight is the colour
  CHECK(al[1] == Approx(0.6f).margin(1e-5));
  const float* n = find(layers, "normal").at(centre);
  CHECK(n[2] == Approx(-1).margin(1e-3));  // towards the camera
  CHECK(find(layers, "depth").at(centre)[0] == Approx(4).margin(2e-3));
  const float* p = find(layers, "position").at(centre);
  CHECK(p[2] == Approx(-1).margin(2e-3));
  CHECK(std::fabs(p[0]) < 0.02f);
  CHECK(find(layers, "material_id").at(centre)[0] >= 1);

  CHECK(find(layers, "albedo").at(corner)[0] == Approx(0.3f));  // the sky's radiance
  CHECK(std::isinf(find(layers, "depth").at(corner)[0]));
  CHECK(find(layers, "material_id").at(corner)[0] == 0);
  CHECK(find(layers, "position").at(corner)[0] == 0);
}

TEST_CASE("aov: mirrors show the albedo of what they reflect, times their colour", "[aov]") {
  auto mirror = std::make_shared<MaterialDesc>();
  mirror->type = MaterialType::Mirror;
  mirror->color.value = Rgb(0.9f, 0.5f, 0.25f);
  const auto scene = sphere_scene(mirror);
  const auto layers = aovs_of(*scene);
  const size_t centre = size_t(kSize / 2) * kSize + kSize / 2;
  const float* al = find(layers, "albedo").at(centre);
  // The centre reflects the sky behind the camera (0.3).
  CHECK(al[0] == Approx(0.9f * 0.3f).margin(1e-4));
  CHECK(al[1] == Approx(0.5f * 0.3f).margin(1e-4));
  CHECK(al[2] == Approx(0.25f * 0.3f).margin(1e-4));
  CHECK(find(layers, "depth").at(centre)[0] == Approx(4).margin(2e-3));  // depth is the first hit's
}

TEST_CASE("aov: layers are bitwise identical on 1 and 2 threads and depend on the seed", "[aov][determinism]") {
  auto plastic = std::make_shared<MaterialDesc>();
  plastic->type = MaterialType::CoatedDiffuse;
  const auto scene = sphere_scene(plastic);
  std::vector<ImageLayer> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = aovs_of(*scene, 4);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = aovs_of(*scene, 4);
  }
  REQUIRE(one.size() == two.size());
  for (size_t i = 0; i < one.size(); ++i) {
    INFO(one[i].name);
    REQUIRE(one[i].values.size() == two[i].values.size());
    CHECK(std::memcmp(one[i].values.data(), two[i].values.data(), one[i].values.size() * sizeof(float)) == 0);
  }
  const auto other = aovs_of(*scene, 4, 1);
  // Plastic's albedo is estimated by sampling its two lobes: another seed gives other estimates.
  CHECK(std::memcmp(one[0].values.data(), other[0].values.data(), one[0].values.size() * sizeof(float)) != 0);
}

TEST_CASE("aov: emission is what area lights send to the camera, exact at an emitter's edge", "[aov]") {
  SceneBuilder b;
  ShapeDesc lamp = sphere_shape(1, Transform(), matte(0.5f));
  lamp.emission = Rgb(4, 2, 1);
  b.add_shape(lamp);
  b.add_light(uniform_sky(Rgb(0.3f)));
  const auto scene = b.flatten();
  const auto layers = aovs_of(*scene, 4);
  const ImageLayer& e = find(layers, "emission");
  const size_t centre = size_t(kSize / 2) * kSize + kSize / 2;
  CHECK(e.at(centre)[0] == Approx(4));
  CHECK(e.at(centre)[2] == Approx(1));
  CHECK(e.at(0)[0] == 0);  // the sky is not in it
  // Along the centre row the sphere's outline is crossed once on each side: there the pixel's emission is its
  // covered fraction (from the edge estimate), between 0 and the full radiance, and monotone across the edge.
  int partial = 0;
  for (int x = 0; x < kSize; ++x) {
    const float v = e.at(size_t(kSize / 2) * kSize + size_t(x))[0];
    partial += v > 0.05f && v < 3.95f;
  }
  CHECK(partial >= 2);
}
