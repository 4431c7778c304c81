// White furnaces for every material type through the whole renderer (wavefront kernels, material resolution):
// a sphere under a uniform infinite light of radiance 1. Lossless materials (Lambert with albedo 1, mirror,
// smooth and thin glass) must render exactly 1; single-scattering microfacet models lose some energy at high
// roughness but must never create any (<= 1). Mixes render the mixture of their parts.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <string>

#include "render/render.h"
#include "scene/builder.h"
#include "scene_helpers.h"

using namespace torte;
using namespace torte::test;

namespace {

std::shared_ptr<MaterialDesc> material(MaterialType type, Rgb color = Rgb(1)) {
  auto m = std::make_shared<MaterialDesc>();
  m->type = type;
  m->color.value = color;
  return m;
}

std::shared_ptr<MaterialDesc> with_roughness(std::shared_ptr<MaterialDesc> m, float roughness) {
  m->roughness.u.value = m->roughness.v.value = roughness;
  return m;
}

// Mean radiance over the pixels well inside the unit sphere's silhouette, seen by an orthographic camera.
double furnace(std::shared_ptr<const MaterialDesc> m, int spp = 64, int max_depth = 200,
               IntegratorKind integrator = IntegratorKind::Path) {
  SceneBuilder b;
  ShapeDesc s;
  s.kind = ShapeDesc::Kind::Quadric;
  s.quadric.kind = QuadricKind::Sphere;
  s.quadric.radius = 1;
  s.material = std::move(m);
  b.add_shape(s);
  b.add_light(uniform_sky(Rgb(1)));
  RenderSettings rs;
  rs.width = rs.height = 24;
  rs.spp = spp;
  rs.max_depth = max_depth;
  rs.integrator = integrator;
  const Image img = render_view(*b.flatten(), furnace_camera(), rs).image;
  return furnace_sphere_mean(img, [](const Rgb& c) { return double(c.average()); });
}

}  // namespace

TEST_CASE("furnace: lossless materials render exactly the sky", "[render][furnace][material]") {
  CHECK(furnace(material(MaterialType::Lambert)) == Approx(1).epsilon(0.01));
  CHECK(furnace(material(MaterialType::Mirror)) == Approx(1).epsilon(1e-4));
  CHECK(furnace(material(MaterialType::Dielectric)) == Approx(1).epsilon(0.01));
  CHECK(furnace(material(MaterialType::ThinDielectric)) == Approx(1).epsilon(0.01));
  auto dense = material(MaterialType::Dielectric);
  dense->eta.value = 2.4f;  // diamond: long internal paths under total internal reflection
  CHECK(furnace(dense, 64, 1000) == Approx(1).epsilon(0.02));
}

TEST_CASE("furnace: tints and albedos scale the result (the test can fail)", "[render][furnace][material]") {
  CHECK(furnace(material(MaterialType::Lambert, Rgb(0.3f))) == Approx(0.3).epsilon(0.01));
  CHECK(furnace(material(MaterialType::Mirror, Rgb(0.5f))) == Approx(0.5).epsilon(1e-3));
}

TEST_CASE("furnace: microfacet and layered materials never create energy", "[render][furnace][material]") {
  for (const float r : {0.05f, 0.4f, 1.0f}) {
    INFO("roughness " << r);
    // A conductor with a huge extinction coefficient reflects (almost) everything: only the single-scattering
    // microfacet model loses energy (light that would scatter between microfacets), a lot at alpha = 1: this
    // is the documented limit of Walter et al.'s model, measured here at about 0.37 for roughness 1.
    auto metal = with_roughness(material(MaterialType::Conductor), r);
    metal->eta_rgb.value = Rgb(1);
    metal->k.value = Rgb(1000);
    const double m = furnace(metal);
    CHECK(m <= 1.01);
    CHECK(m > (r < 0.5f ? 0.93 : 0.3));
    const double g = furnace(with_roughness(material(MaterialType::Dielectric), r), 64, 200);
    CHECK(g <= 1.01);
    CHECK(g > (r < 0.5f ? 0.9 : 0.3));
    const double p = furnace(with_roughness(material(MaterialType::CoatedDiffuse), r));
    CHECK(p <= 1.01);
    CHECK(p > 0.8);
  }
  auto on = material(MaterialType::OrenNayar);
  on->sigma.value = 30;
  const double o = furnace(on);
  CHECK(o <= 1.01);
  CHECK(o > 0.8);  // qualitative Oren-Nayar loses some energy at sigma = 30 degrees (measured 0.83)
}

TEST_CASE("furnace: a mix renders the mixture of its materials", "[render][furnace][material]") {
  auto mix = material(MaterialType::Mix);
  mix->a = material(MaterialType::Lambert, Rgb(0.2f));
  mix->b = material(MaterialType::Lambert, Rgb(0.8f));
  mix->amount.value = 0.25f;
  CHECK(furnace(mix, 128) == Approx(0.75 * 0.2 + 0.25 * 0.8).epsilon(0.015));
  // Nested: mix(mirror 0.5, mix(lambert 0.2, lambert 0.8, 0.25), 0.5).
  auto outer = material(MaterialType::Mix);
  outer->a = material(MaterialType::Mirror, Rgb(0.5f));
  outer->b = mix;
  outer->amount.value = 0.5f;
  CHECK(furnace(outer, 128) == Approx(0.5 * 0.5 + 0.5 * 0.35).epsilon(0.015));
}

TEST_CASE("direct lighting follows specular chains and stops at the first diffuse event", "[render][furnace][material]") {
  const auto direct = IntegratorKind::Direct;
  CHECK(furnace(material(MaterialType::Mirror), 16, 200, direct) == Approx(1).epsilon(1e-4));
  CHECK(furnace(material(MaterialType::Dielectric), 64, 200, direct) == Approx(1).epsilon(0.01));
  CHECK(furnace(material(MaterialType::Lambert, Rgb(0.6f)), 64, 200, direct) == Approx(0.6).epsilon(0.01));
  // A mirror in front of a white Lambert sphere would need two events; here: max_depth 0 shows no surface light.
  CHECK(furnace(material(MaterialType::Mirror), 16, 0, direct) == Approx(0).margin(1e-6));
}

TEST_CASE("lt furnace: light tracing renders every non-specular material type as path does", "[render][furnace][material][lt]") {
  // BSDFs in TransportMode::Importance (rough glass scales by eta^2 the other way), lobe selection of layered
  // materials, batched evaluation (Oren-Nayar, conductors): the sphere's mean against path tracing's.
  auto on = material(MaterialType::OrenNayar, Rgb(0.8f));
  on->sigma.value = 30;
  auto mix = material(MaterialType::Mix);
  mix->a = material(MaterialType::Lambert, Rgb(0.2f));
  mix->b = with_roughness(material(MaterialType::Conductor), 0.7f);
  const std::pair<const char*, std::shared_ptr<MaterialDesc>> cases[] = {
      {"lambert", material(MaterialType::Lambert, Rgb(0.7f))},
      {"oren-nayar", on},
      // Glossy vertices make light tracing heavy-tailed (means converge from below: roughness 0.2 gave 0.88 at
      // 256 and 0.94 at 1024 light paths per pixel against path's 0.997), so the conductor here is rough.
      {"rough conductor", with_roughness(material(MaterialType::Conductor), 0.8f)},
      {"coated diffuse", with_roughness(material(MaterialType::CoatedDiffuse, Rgb(0.6f)), 0.4f)},
      {"rough glass", with_roughness(material(MaterialType::Dielectric), 0.5f)},
      {"mix", mix}};
  for (const auto& [name, m] : cases) {
    // Rough glass is the noisiest (about 2.3 % between seeds at 512 light paths per pixel, mean of 8 seeds
    // within 0.3 % of path): more paths and a wider margin.
    const bool glass = std::string(name) == "rough glass";
    const double path = furnace(m, 128), lt = furnace(m, glass ? 1024 : 256, 200, IntegratorKind::Lt);
    INFO(name << ": lt " << lt << ", path " << path);
    CHECK(lt == Approx(path).epsilon(glass ? 0.05 : 0.03));
  }
  // A mirror seen by the camera is what light tracing cannot render: only the sky around it.
  CHECK(furnace(material(MaterialType::Mirror), 16, 200, IntegratorKind::Lt) == Approx(0).margin(1e-6));
}
