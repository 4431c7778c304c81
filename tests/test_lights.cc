// Lights (spot, distant, sphere solid-angle sampling, environment map, Preetham sky): chi-square tests of every
// sampling routine against its documented density (tests/chi2.h), light_pdf against the pdf sample_light reports,
// power estimates, and small end-to-end renders. The thin-lens camera's tests are in test_camera.cc.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <vector>

#include "camera/camera.h"
#include "chi2.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "film/image.h"
#include "light/environment.h"
#include "light/light.h"
#include "light/sky.h"
#include "render/render.h"
#include "scene/builder.h"
#include "scene_helpers.h"
#include "test_random.h"

using namespace torte;
using torte::test::next_2d;
using torte::test::integrate;
using namespace torte::test;
using torte::test::chi2_test;
using torte::test::Chi2Result;

namespace {

constexpr int kChi2Tests = 5;  // chi-square tests in this file (Sidak correction)
constexpr double kPiD = 3.14159265358979323846;

// TORTE_CHI2_VERBOSE=1 prints every statistic.
Chi2Result run_chi2(const std::vector<double>& observed, const std::vector<double>& expected) {
  Chi2Result r = chi2_test(observed, expected, 0.01, kChi2Tests);
  if (std::getenv("TORTE_CHI2_VERBOSE")) std::printf("%s\n", r.message.c_str());
  return r;
}

// An orthographic camera 3 units above the origin looking straight down (+z is the image's up), `extent` wide.
CameraDesc top_down_camera(float extent) {
  CameraDesc cam;
  cam.kind = CameraKind::Orthographic;
  cam.camera_to_world = look_at({0, 3, 0}, {0, 0, 0}, {0, 0, 1});
  cam.extent = extent;
  return cam;
}

ShapeDesc quad_shape(float y, float half, std::shared_ptr<MaterialDesc> m) {
  ShapeDesc q;
  q.kind = ShapeDesc::Kind::Mesh;
  q.mesh = std::make_shared<TriangleMesh>(
      make_polygon({{-half, y, -half}, {-half, y, half}, {half, y, half}, {half, y, -half}}));
  q.material = std::move(m);
  return q;
}

// A synthetic environment map with strong features in both hemispheres: a dim gradient, a black band, a very
// bright small "sun" below the horizon and a bright patch near the top pole.
Image feature_image(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Rgb c(0.05f + 0.3f * float(x) / float(w), 0.1f, 0.2f * float(y) / float(h));
      if (y == h / 2 - 1) c = Rgb(0);  // black band just above the horizon
      if (y == 3 * h / 4 && (x == w / 3 || x == w / 3 + 1)) c = Rgb(200, 150, 100);
      if (y == 0 && x < w / 4) c = Rgb(20);
      img.at(x, y) = c;
    }
  return img;
}

// Samples n directions from sample(u) and tests them in the light's own (u, v) = (phi/2pi, theta/pi) space on an
// nu x nv grid (aligned with the texels of the tabulated distribution, so the density times sin(theta) is
// constant within a bin), against the solid-angle density pdf(world direction). The expected count of a bin is
// n times the integral of pdf over its solid angle: pdf(d(u,v)) 2 pi^2 sin(pi v) du dv.
Chi2Result test_equirect(const std::function<bool(Vec2f, Vec3f*)>& sample,
                         const std::function<double(Vec3f)>& pdf, const Transform& to_world, int nu, int nv,
                         int n) {
  std::vector<double> observed(size_t(nu * nv) + 1, 0.0), expected(size_t(nu * nv) + 1, 0.0);
  Pcg32 rng(7);
  for (int i = 0; i < n; ++i) {
    Vec3f wi;
    if (!sample(next_2d(rng), &wi)) continue;
    if (std::fabs(length(wi) - 1) > 1e-4f) {
      observed.back() += 1;
      continue;
    }
    const Vec2f uv = equirect_uv(normalize(to_world.apply_inverse_vector(wi)));
    const int x = std::clamp(int(uv.x * float(nu)), 0, nu - 1), y = std::clamp(int(uv.y * float(nv)), 0, nv - 1);
    observed[size_t(y * nu + x)] += 1;
  }
  for (int y = 0; y < nv; ++y)
    for (int x = 0; x < nu; ++x) {
      const double integral = integrate(
          [&](double v) {
            return integrate(
                [&](double u) {
                  const Vec3f d = normalize(to_world.apply_vector(equirect_direction(Vec2f(float(u), float(v)))));
                  return pdf(d) * 2 * kPiD * kPiD * std::sin(kPiD * v);
                },
                double(x) / nu, double(x + 1) / nu);
          },
          double(y) / nv, double(y + 1) / nv);
      expected[size_t(y * nu + x)] = n * integral;
    }
  return run_chi2(observed, expected);
}

// Integral of a solid-angle density over the sphere (midpoint rule in cos theta and phi).
double sphere_integral(const std::function<double(Vec3f)>& pdf, int n_cos, int n_phi) {
  double sum = 0;
  for (int i = 0; i < n_cos; ++i) {
    const double z = -1 + 2 * (i + 0.5) / n_cos, s = std::sqrt(std::max(0.0, 1 - z * z));
    for (int j = 0; j < n_phi; ++j) {
      const double phi = 2 * kPiD * (j + 0.5) / n_phi;
      sum += pdf(Vec3f(float(s * std::cos(phi)), float(z), float(s * std::sin(phi))));
    }
  }
  return sum * (2.0 / n_cos) * (2 * kPiD / n_phi);
}

// Chi-square of directions around `axis` binned by (cos theta, phi) over [cos_lo, 1], against a uniform cone.
Chi2Result test_uniform_cone(const std::function<Vec3f(Vec2f)>& sample, Vec3f axis, double one_minus_cos, int n,
                             uint64_t seed = 3) {
  const int nc = 10, np = 20;
  const Frame f = Frame::from_z(axis);
  std::vector<double> observed(size_t(nc * np) + 1, 0.0), expected(size_t(nc * np) + 1, 0.0);
  Pcg32 rng(seed);
  for (int i = 0; i < n; ++i) {
    const Vec3f l = f.to_local(sample(next_2d(rng)));
    const double a = 1 - double(l.z);  // in [0, one_minus_cos]
    if (a < -1e-6 || a > one_minus_cos * (1 + 1e-3) + 1e-7) {
      observed.back() += 1;
      continue;
    }
    double phi = std::atan2(double(l.y), double(l.x));
    if (phi < 0) phi += 2 * kPiD;
    const int ic = std::clamp(int(a / one_minus_cos * nc), 0, nc - 1);
    const int ip = std::clamp(int(phi / (2 * kPiD) * np), 0, np - 1);
    observed[size_t(ic * np + ip)] += 1;
  }
  for (size_t k = 0; k + 1 < expected.size(); ++k) expected[k] = double(n) / (nc * np);
  return run_chi2(observed, expected);
}

}  // namespace

TEST_CASE("Distribution2D samples its weights and pdf matches the sample density", "[light][sampling][chi2]") {
  const int nu = 7, nv = 5;
  std::vector<float> w(nu * nv);
  Pcg32 rng(11);
  for (auto& x : w) x = rng.next_float() < 0.2f ? 0.0f : rng.next_float() * 10;
  w[3] = 100;
  const Distribution2D d(w, nu, nv);
  double total = 0;
  for (float x : w) total += x;
  CHECK(d.integral() == Approx(total / (nu * nv)).epsilon(1e-5));
  const int n = 200000;
  std::vector<double> observed(w.size(), 0.0), expected(w.size());
  for (int i = 0; i < n; ++i) {
    float pdf;
    const Vec2f p = d.sample(next_2d(rng), &pdf);
    REQUIRE(p.x >= 0);
    REQUIRE(p.x < 1);
    REQUIRE(p.y >= 0);
    REQUIRE(p.y < 1);
    REQUIRE(pdf == Approx(d.pdf(p)).epsilon(1e-5));
    observed[size_t(int(p.y * nv) * nu + int(p.x * nu))] += 1;
  }
  for (size_t k = 0; k < w.size(); ++k) expected[k] = n * w[k] / total;
  const Chi2Result r = run_chi2(observed, expected);
  INFO(r.message);
  CHECK(r.passed);
  // The density integrates to one over the unit square.
  double sum = 0;
  for (int y = 0; y < nv; ++y)
    for (int x = 0; x < nu; ++x) sum += d.pdf({(x + 0.5f) / nu, (y + 0.5f) / nv}) / (nu * nv);
  CHECK(sum == Approx(1).epsilon(1e-5));
}

TEST_CASE("Environment map: chi-square over the whole sphere, pdf integrates to one", "[light][environment][chi2]") {
  const Image img = feature_image(32, 16);
  const Transform rot = rotate(37, normalize(Vec3f(1, 2, 0.5f)));
  Light l;
  l.kind = LightKind::Environment;
  l.environment = make_environment_map(img, rot, Rgb(2));
  const Scene scene;
  const auto sample = [&](Vec2f u, Vec3f* wi) {
    LightSample s;
    if (!sample_light(scene, l, {0, 0, 0}, u, &s)) return false;
    REQUIRE(s.pdf == Approx(light_pdf(scene, l, {0, 0, 0}, s.wi, nullptr, kInfinity)).epsilon(1e-6));
    REQUIRE(s.radiance == escaped_radiance(l, s.wi));
    REQUIRE_FALSE(s.delta);
    *wi = s.wi;
    return true;
  };
  const auto pdf = [&](Vec3f d) { return double(light_pdf(scene, l, {0, 0, 0}, d, nullptr, kInfinity)); };
  // Bins of half a texel in each direction.
  const Chi2Result r = test_equirect(sample, pdf, rot, 64, 32, 400000);
  INFO(r.message);
  CHECK(r.passed);
  CHECK(sphere_integral(pdf, 600, 1200) == Approx(1).epsilon(0.01));
  // The bright texel below the horizon is sampled, and its radiance comes back on escaped rays.
  const Vec3f sun = normalize(rot.apply_vector(equirect_direction({(32 / 3 + 0.5f) / 32, (12 + 0.5f) / 16})));
  CHECK(sun.y != 0);
  CHECK(escaped_radiance(l, sun) == Rgb(400, 300, 200));
  CHECK(pdf(sun) > 1);
  // Power: the bounding-sphere cross-section times the integral of the average radiance.
  double integral = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) {
      const double t0 = kPiD * y / 16, t1 = kPiD * (y + 1) / 16;
      integral += 2 * img.at(x, y).average() * (2 * kPiD / 32) * (std::cos(t0) - std::cos(t1));
    }
  CHECK(l.environment->integral == Approx(integral).epsilon(0.01));
}

TEST_CASE("Sky: chi-square of the tabulated dome, sun probability, colours", "[light][sky][chi2]") {
  SkyParams p;
  p.sun_direction = normalize(Vec3f(0.3f, 0.5f, -0.6f));
  p.turbidity = 3;
  p.table_width = 48;
  p.table_height = 24;
  {
    p.sun = false;
    Light l;
    l.kind = LightKind::Sky;
    l.sky = make_sky(p);
    const Scene scene;
    const auto sample = [&](Vec2f u, Vec3f* wi) {
      LightSample s;
      if (!sample_light(scene, l, {0, 0, 0}, u, &s)) return false;
      REQUIRE(s.wi.y >= 0);
      REQUIRE(s.pdf == Approx(light_pdf(scene, l, {0, 0, 0}, s.wi, nullptr, kInfinity)).epsilon(1e-6));
      *wi = s.wi;
      return true;
    };
    const auto pdf = [&](Vec3f d) { return double(l.sky->pdf(d)); };
    const Chi2Result r = test_equirect(sample, pdf, Transform(), 48, 24, 300000);
    INFO(r.message);
    CHECK(r.passed);
    CHECK(sphere_integral(pdf, 400, 800) == Approx(1).epsilon(0.01));
  }
  p.sun = true;
  p.sun_radius_degrees = 2;
  const auto sky = make_sky(p);
  CHECK(sky->sun_probability > 0.3f);
  CHECK(sky->sun_probability <= 0.95f);
  // The fraction of samples in the sun's cone is the sun probability plus the table's (small) share there.
  Pcg32 rng(5);
  const int n = 100000;
  int in_sun = 0;
  for (int i = 0; i < n; ++i) {
    Vec3f wi;
    float pdf;
    if (sky->sample(next_2d(rng), &wi, &pdf) && sky->in_sun(wi)) ++in_sun;
    REQUIRE(pdf == Approx(sky->pdf(wi)).epsilon(1e-6));
  }
  const double table_share = 2 * kPiD * sky->sun_one_minus_cos * sky->sampling.pdf(sky->sun_dir);
  const double expect = sky->sun_probability + (1 - sky->sun_probability) * table_share;
  CHECK(std::fabs(in_sun / double(n) - expect) < 5 * std::sqrt(expect * (1 - expect) / n) + 0.01);
  CHECK(sphere_integral([&](Vec3f d) { return double(sky->pdf(d)); }, 800, 1600) == Approx(1).epsilon(0.02));
  // Physically plausible colours: a blue zenith, a sun that reddens towards the horizon, black below.
  const Rgb zenith = sky->sky_radiance({0, 1, 0});
  CHECK(zenith.b > zenith.r);
  CHECK(zenith.average() > 0);
  CHECK(sky->sky_radiance({0, -0.5f, 0.866f}).is_black());
  SkyParams low = p;
  low.sun_direction = {0, std::sin(5 * kPi / 180), std::cos(5 * kPi / 180)};
  const auto evening = make_sky(low);
  CHECK(evening->sun_radiance.r / evening->sun_radiance.b > 1.5f * sky->sun_radiance.r / sky->sun_radiance.b);
  CHECK(evening->sun_radiance.average() < sky->sun_radiance.average());
  // Midday sun illuminance (radiance x solid angle, in kcd/m^2 x sr = klux) near 100 klux.
  SkyParams noon;
  noon.sun_direction = {0, 1, 0};
  const auto s0 = make_sky(noon);
  const float klux = s0->sun_radiance.average() / noon.scale * 2 * kPi * s0->sun_one_minus_cos;
  CHECK(klux > 70);
  CHECK(klux < 130);
  CHECK_THROWS(make_sky(SkyParams{{0, -1, 0.2f}}));
  SkyParams bad;
  bad.turbidity = 20;
  CHECK_THROWS(make_sky(bad));
}

TEST_CASE("Spot light: falloff, emission sampling chi-square, power", "[light][spot][chi2]") {
  Light l;
  l.kind = LightKind::Spot;
  l.position = {0, 2, 0};
  l.direction = normalize(Vec3f(0.2f, -1, 0.1f));
  l.radiance = Rgb(3);
  l.cos_total = std::cos(30 * kPi / 180);
  l.cos_falloff_start = std::cos(20 * kPi / 180);
  const Scene scene;
  // On the axis: intensity / d^2; beyond the cone: nothing; in between: monotonic.
  LightSample s;
  REQUIRE(sample_light(scene, l, l.position + l.direction * 2, {0.5f, 0.5f}, &s));
  CHECK(s.delta);
  CHECK(s.radiance.g == Approx(3.0f / 4));
  const Frame f = Frame::from_z(l.direction);
  float prev = 2;
  for (int deg = 0; deg <= 40; ++deg) {
    const float t = float(deg) * kPi / 180;
    const Vec3f dir = f.to_world({std::sin(t), 0, std::cos(t)});
    const bool lit = sample_light(scene, l, l.position + dir, {0.5f, 0.5f}, &s);
    const float v = lit ? s.radiance.g / 3 : 0;
    if (deg <= 20) CHECK(v == Approx(1));
    if (deg >= 31) CHECK(v == 0);
    CHECK(v <= prev + 1e-6f);
    prev = v;
  }
  CHECK(light_pdf(scene, l, {0, 0, 0}, {0, 1, 0}, nullptr, 1) == 0);
  // Emission sampling is uniform in the cone.
  const double omc = 1 - double(l.cos_total);
  const Chi2Result r = test_uniform_cone(
      [&](Vec2f u) {
        float pdf;
        const Vec3f d = sample_spot_emission(l, u, &pdf);
        REQUIRE(pdf == Approx(1 / (2 * kPiD * omc)).epsilon(1e-4));
        return d;
      },
      l.direction, omc, 200000);
  INFO(r.message);
  CHECK(r.passed);
  // Power = integral of intensity x falloff over the sphere.
  double power = 0;
  const int steps = 20000;
  for (int i = 0; i < steps; ++i) {
    const double t = (i + 0.5) / steps * kPiD;
    power += 3 * spot_falloff(l, float(std::cos(t))) * 2 * kPiD * std::sin(t) * (kPiD / steps);
  }
  CHECK(light_power(scene, l) == Approx(power).epsilon(2e-3));
}

TEST_CASE("Sphere area light: solid-angle sampling chi-square, pdf matches, inside falls back to area",
          "[light][sphere][chi2]") {
  SceneBuilder b;
  ShapeDesc lamp = sphere_shape(0.5f, translate({1, 2, 3}) * rotate(20, {1, 1, 0}) * scale({2, 2, 2}), matte(0));
  lamp.emission = Rgb(5);
  b.add_shape(lamp);
  const auto scene = b.flatten();
  REQUIRE(scene->lights.size() == 1);
  const Light& l = scene->lights[0];
  REQUIRE(l.sphere_cone);
  CHECK(l.sphere_radius == Approx(1));
  CHECK(l.sphere_center.z == Approx(3));
  const Vec3f p{-1, 0.5f, 0};
  const float d = length(l.sphere_center - p);
  const double omc = 1 - std::sqrt(1 - 1.0 / (double(d) * d));
  const auto sample = [&](Vec2f u) {
    LightSample s;
    REQUIRE(sample_light(*scene, l, p, u, &s));
    // The direction reaches the sphere at the reported distance, and light_pdf agrees.
    Ray ray{p, s.wi, kInfinity};
    Hit hit;
    if (scene->intersect(ray, &hit)) {  // grazing samples may miss by rounding
      CHECK(hit.t == Approx(s.distance).epsilon(1e-3));
      const SurfaceHit sh = scene->surface(ray, hit);
      CHECK(light_pdf(*scene, l, p, s.wi, &sh, hit.t) == Approx(s.pdf).epsilon(1e-5));
    }
    return s.wi;
  };
  const Chi2Result r = test_uniform_cone(sample, normalize(l.sphere_center - p), omc, 100000);
  INFO(r.message);
  CHECK(r.passed);
  // Inside: area sampling, and light_pdf still matches.
  const Vec3f inside = l.sphere_center + Vec3f(0.2f, -0.1f, 0.3f);
  Pcg32 rng(9);
  for (int i = 0; i < 200; ++i) {
    LightSample s;
    if (!sample_light(*scene, l, inside, next_2d(rng), &s)) continue;
    Ray ray{inside, s.wi, kInfinity};
    Hit hit;
    REQUIRE(scene->intersect(ray, &hit));
    const SurfaceHit sh = scene->surface(ray, hit);
    CHECK(light_pdf(*scene, l, inside, s.wi, &sh, hit.t) == Approx(s.pdf).epsilon(1e-3));
  }
  // A non-uniformly scaled sphere keeps area sampling.
  SceneBuilder b2;
  ShapeDesc egg = sphere_shape(0.5f, scale({1, 2, 1}), matte(0));
  egg.emission = Rgb(1);
  b2.add_shape(egg);
  CHECK_FALSE(b2.flatten()->lights[0].sphere_cone);
}

TEST_CASE("light_pdf equals the sample pdf for every non-delta light", "[light]") {
  SceneBuilder b;
  ShapeDesc panel = quad_shape(1.5f, 0.5f, matte(0));
  panel.emission = Rgb(2);
  panel.two_sided = true;
  b.add_shape(panel);
  ShapeDesc disk;
  disk.kind = ShapeDesc::Kind::Quadric;
  disk.quadric.kind = QuadricKind::Disk;
  disk.quadric.radius = 0.4f;
  disk.transform = translate({0, -1.5f, 0}) * rotate(-90, {1, 0, 0});
  disk.material = matte(0);
  disk.emission = Rgb(1);
  b.add_shape(disk);
  ShapeDesc ball = sphere_shape(0.3f, translate({1.2f, 0, 0}), matte(0));
  ball.emission = Rgb(3);
  b.add_shape(ball);
  Light env;
  env.kind = LightKind::Environment;
  env.environment = make_environment_map(feature_image(16, 8), rotate(60, {0, 0, 1}), Rgb(1));
  b.add_light(env);
  Light sky;
  sky.kind = LightKind::Sky;
  SkyParams sp;
  sp.sun_direction = {0.2f, 0.6f, 0.3f};
  sp.sun_radius_degrees = 1;
  sky.sky = make_sky(sp);
  b.add_light(sky);
  b.add_light(uniform_sky(Rgb(0.5f)));
  const auto scene = b.flatten();
  const Vec3f p{0.1f, 0.2f, -0.1f};
  Pcg32 rng(4);
  for (size_t li = 0; li < scene->lights.size(); ++li) {
    const Light& l = scene->lights[li];
    INFO("light " << li);
    int checked = 0;
    for (int i = 0; i < 300; ++i) {
      LightSample s;
      if (!sample_light(*scene, l, p, next_2d(rng), &s)) continue;
      REQUIRE_FALSE(s.delta);
      if (is_infinite_light(l)) {
        CHECK(light_pdf(*scene, l, p, s.wi, nullptr, kInfinity) == Approx(s.pdf).epsilon(1e-5));
        CHECK(s.radiance == escaped_radiance(l, s.wi));
        ++checked;
        continue;
      }
      Ray ray{p, s.wi, kInfinity};
      Hit hit;
      if (!scene->intersect(ray, &hit)) continue;
      const SurfaceHit sh = scene->surface(ray, hit);
      if (scene->objects[sh.object].area_light != int(li)) continue;  // another emitter in front
      CHECK(light_pdf(*scene, l, p, s.wi, &sh, hit.t) == Approx(s.pdf).epsilon(2e-3));
      ++checked;
    }
    CHECK(checked > 100);
    CHECK(light_power(*scene, l) > 0);
  }
}

TEST_CASE("Distant light: delta, irradiance, power from the scene's bounding sphere", "[light]") {
  Light l;
  l.kind = LightKind::Distant;
  l.direction = normalize(Vec3f(0, -1, 1));
  l.radiance = Rgb(2);
  SceneBuilder b;
  b.add_shape(quad_shape(0, 1, matte(0.5f)));
  b.add_light(l);
  const auto scene = b.flatten();
  LightSample s;
  REQUIRE(sample_light(*scene, scene->lights[0], {0, 0, 0}, {0.3f, 0.3f}, &s));
  CHECK(s.delta);
  CHECK(s.distance == kInfinity);
  CHECK(s.wi.y == Approx(std::sqrt(0.5f)));
  CHECK(light_power(*scene, scene->lights[0]) == Approx(kPi * scene->radius() * scene->radius() * 2));
  RenderSettings rs;
  rs.width = rs.height = 8;
  rs.spp = 4;
  rs.max_depth = 1;
  const Image img = render_view(*scene, top_down_camera(1), rs).image;
  // Lambert: albedo / pi x irradiance x cos(45 degrees).
  CHECK(img.at(4, 4).g == Approx(0.5f / kPi * 2 * std::sqrt(0.5f)).epsilon(1e-3));
}

TEST_CASE("Spot light renders intensity / d^2 under the axis", "[light][spot][render]") {
  SceneBuilder b;
  b.add_shape(quad_shape(0, 2, matte(0.5f)));
  Light l;
  l.kind = LightKind::Spot;
  l.position = {0, 2, 0};
  l.direction = {0, -1, 0};
  l.radiance = Rgb(8);
  l.cos_total = std::cos(20 * kPi / 180);
  l.cos_falloff_start = std::cos(15 * kPi / 180);
  b.add_light(l);
  const auto scene = b.flatten();
  RenderSettings rs;
  rs.width = rs.height = 16;
  rs.spp = 4;
  rs.max_depth = 1;
  const Image img = render_view(*scene, top_down_camera(4), rs).image;
  CHECK(img.at(8, 8).g == Approx(0.5f / kPi * 8 / 4).epsilon(2e-2));  // within the cone (a few degrees off axis)
  CHECK(img.at(0, 0).g == 0);  // corner: outside the cone
}

TEST_CASE("furnace: a constant environment map renders like the uniform infinite light", "[light][environment][render]") {
  auto render_with = [](const Light& light) {
    SceneBuilder b;
    b.add_shape(sphere_shape(1, Transform(), matte(0.8f)));
    b.add_light(light);
    const auto scene = b.flatten();
    RenderSettings s;
    s.width = s.height = 24;
    s.spp = 32;
    return render_view(*scene, furnace_camera(), s).image;
  };
  Light uni;
  uni.kind = LightKind::Infinite;
  uni.radiance = Rgb(1);
  Image ones(8, 4);
  for (auto& px : ones.pixels) px = Rgb(1);
  Light env;
  env.kind = LightKind::Environment;
  env.environment = make_environment_map(ones, rotate(30, {1, 0, 0}), Rgb(1));
  const Image a = render_with(uni), c = render_with(env);
  const double ma = furnace_sphere_mean_green(a), mc = furnace_sphere_mean_green(c);
  CHECK(ma == Approx(0.8).epsilon(0.03));
  CHECK(mc == Approx(ma).epsilon(0.03));
  CHECK(c.at(0, 0).g == Approx(1));  // the background is the map
}

TEST_CASE("MIS with environment and sky lights: a lit plane matches the irradiance integral", "[light][render]") {
  // Direct light only (max_depth 1) on an upward-facing Lambert plane seen from above: the pixel value is
  // albedo / pi x the integral of escaped radiance x cos(theta) over the upper hemisphere. Light and BSDF samples
  // are combined by MIS, so a light_pdf that disagreed with sample_light would bias the result.
  auto check = [](const Light& light, const char* what) {
    INFO(what);
    SceneBuilder b;
    b.add_shape(quad_shape(0, 1, matte(0.5f)));
    b.add_light(light);
    const auto scene = b.flatten();
    RenderSettings rs;
    rs.width = rs.height = 8;
    rs.spp = 256;
    rs.max_depth = 1;
    const Image img = render_view(*scene, top_down_camera(0.2f), rs).image;
    double mean = 0;
    for (const Rgb& c : img.pixels) mean += c.g;
    mean /= double(img.pixels.size());
    // Upper hemisphere, midpoint rule in (cos theta, phi) around +y.
    double e = 0;
    const int nc = 600, np = 1200;
    for (int i = 0; i < nc; ++i) {
      const double c = (i + 0.5) / nc, s = std::sqrt(1 - c * c);
      for (int j = 0; j < np; ++j) {
        const double phi = 2 * kPiD * (j + 0.5) / np;
        const Vec3f w(float(s * std::cos(phi)), float(c), float(s * std::sin(phi)));
        e += escaped_radiance(scene->lights[0], w).g * c;
      }
    }
    e *= (1.0 / nc) * (2 * kPiD / np);
    CHECK(mean == Approx(0.5 / kPiD * e).epsilon(0.03));
  };
  Light env;
  env.kind = LightKind::Environment;
  env.environment = make_environment_map(feature_image(32, 16), rotate(120, {1, 0, 0}), Rgb(1));
  check(env, "environment");
  Light sky;
  sky.kind = LightKind::Sky;
  SkyParams p;
  p.sun_direction = {0.3f, 0.6f, 0.2f};
  p.sun_radius_degrees = 1.5f;  // the sun's contribution must be resolved by the midpoint rule above
  sky.sky = make_sky(p);
  check(sky, "sky");
}
