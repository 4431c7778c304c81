// Camera importance for light tracing (camera/camera.h): We, pdf_we and sample_wi for the perspective and
// orthographic cameras, with and without a thin lens. The central check integrates We over a plane in front of
// the camera the way a light tracer does (uniform points, sample_wi, |cos| We / pdf): every pixel must receive
// 1 / (width * height) of the importance, so a uniform emitter of radiance 1 gives a white image.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "camera/camera.h"
#include "core/rng.h"
#include "core/transform.h"
#include "test_random.h"

using namespace torte;
using torte::test::next_2d;
using torte::test::random_direction;

namespace {

struct Case {
  const char* name;
  CameraKind kind;
  float aperture;
};
constexpr Case kCases[] = {{"perspective", CameraKind::Perspective, 0},
                           {"perspective thin lens", CameraKind::Perspective, 0.3f},
                           {"orthographic", CameraKind::Orthographic, 0},
                           {"orthographic thin lens", CameraKind::Orthographic, 0.3f}};

constexpr int kW = 4, kH = 3;

Camera make_camera(const Case& c) {
  CameraDesc d;
  d.kind = c.kind;
  d.camera_to_world = look_at({0.5f, 1, -2}, {0.2f, 0.7f, 2}, {0, 1, 0});
  d.fov_degrees = 70;  // wide: the cos^4 falloff of We matters at the corners
  d.extent = 3;
  d.aperture_radius = c.aperture;
  d.focus_distance = 2.5f;
  return Camera(d, kW, kH);
}

}  // namespace

TEST_CASE("Camera importance: a light tracer's integral over a plane gives 1/(W*H) per pixel", "[camera][lt]") {
  for (const Case& c : kCases) {
    INFO(c.name);
    const Camera cam = make_camera(c);
    const Transform& c2w = cam.desc().camera_to_world;
    // A square at camera-space depth 4 (beyond and in front of the focus plane both get tested through the lens
    // blur), much larger than the view and its blur.
    const float depth = 4, half = c.kind == CameraKind::Perspective ? 5.0f : 2.5f, area = 4 * half * half;
    const Vec3f normal = normalize(c2w.apply_vector({0, 0, 1}));
    std::vector<double> pixel(kW * kH, 0);
    Pcg32 rng(7);
    const int n = 600000;
    for (int i = 0; i < n; ++i) {
      const Vec2f u = next_2d(rng);
      const Vec3f p = c2w.apply_point({(2 * u.x - 1) * half, (2 * u.y - 1) * half, depth});
      CameraWiSample s;
      if (!cam.sample_wi(p, next_2d(rng), &s)) continue;
      REQUIRE(s.raster.x >= 0);
      REQUIRE(s.raster.x < kW);
      REQUIRE(s.raster.y >= 0);
      REQUIRE(s.raster.y < kH);
      // Radiance 1 leaving p towards the lens, point density 1/area.
      pixel[size_t(int(s.raster.y)) * kW + size_t(int(s.raster.x))] += std::fabs(dot(s.wi, normal)) * s.we / s.pdf * area;
    }
    for (int k = 0; k < kW * kH; ++k) {
      INFO("pixel " << k);
      CHECK(pixel[size_t(k)] * kW * kH / n == Approx(1).epsilon(0.03));
    }
  }
}

TEST_CASE("Camera importance: sample_wi and generate_ray describe the same rays", "[camera][lt]") {
  for (const Case& c : kCases) {
    INFO(c.name);
    const Camera cam = make_camera(c);
    const Transform& c2w = cam.desc().camera_to_world;
    Pcg32 rng(3);
    int connected = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3f p = c2w.apply_point({(2 * rng.next_float() - 1) * 4, (2 * rng.next_float() - 1) * 3,
                                       0.5f + 5 * rng.next_float()});
      const Vec2f u = next_2d(rng);
      CameraWiSample s;
      if (!cam.sample_wi(p, u, &s)) continue;
      ++connected;
      // The camera's ray for that raster position and lens sample starts at the lens point and passes p.
      const Ray r = cam.generate_ray(s.raster, u);
      CHECK(length(r.o - s.lens) < 2e-4f * (1 + length(s.lens)));
      const Vec3f to = p - r.o;
      CHECK(length(to - r.d * dot(to, r.d)) < 1e-3f * length(to));
      CHECK(length(s.lens - s.wi * s.distance - p) < 1e-3f * s.distance);
      // We of that ray agrees with the sample's, and lands on the same raster position.
      Vec2f raster;
      const float we = cam.we(r, &raster);
      CHECK(we == Approx(s.we).epsilon(1e-3));
      CHECK(std::fabs(raster.x - s.raster.x) + std::fabs(raster.y - s.raster.y) < 2e-3f);
      float pdf_pos, pdf_dir;
      cam.pdf_we(r, &pdf_pos, &pdf_dir);
      // The joint density of generate_ray is We |cos| (importance normalised over the generated rays).
      const float cos = dot(r.d, normalize(c2w.apply_vector({0, 0, 1})));
      if (!s.delta) CHECK(pdf_pos * pdf_dir == Approx(we * cos).epsilon(1e-3));
    }
    CHECK(connected > 200);
    // Behind the camera: no connection.
    CameraWiSample s;
    CHECK_FALSE(cam.sample_wi(c2w.apply_point({0, 0, -1}), {0.5f, 0.5f}, &s));
  }
}

TEST_CASE("Camera importance: the perspective pdf over directions integrates to 1", "[camera][lt]") {
  for (const Case& c : kCases) {
    if (c.kind != CameraKind::Perspective) continue;
    INFO(c.name);
    const Camera cam = make_camera(c);
    const Transform& c2w = cam.desc().camera_to_world;
    Pcg32 rng(11);
    // From the lens centre and from a point off it: the frustum through the plane in focus covers the image.
    for (const Vec2f lens : {Vec2f(0, 0), Vec2f(0.2f, -0.1f)}) {
      if (c.aperture == 0 && lens.x != 0) continue;
      const Vec3f o = c2w.apply_point({lens.x, lens.y, 0});
      double sum = 0;
      const int n = 400000;
      for (int i = 0; i < n; ++i) {
        float pos, dir;
        cam.pdf_we(Ray{o, random_direction(rng), kInfinity}, &pos, &dir);
        sum += dir * 4 * kPi;
        if (dir > 0) CHECK(pos == Approx(1 / (c.aperture > 0 ? kPi * c.aperture * c.aperture : 1)));
      }
      CHECK(sum / n == Approx(1).epsilon(0.02));
    }
  }
}

TEST_CASE("Camera importance: a scaled placement cannot be connected to", "[camera][lt]") {
  CameraDesc d;
  d.camera_to_world = look_at({0, 0, 0}, {0, 0, 1}, {0, 1, 0});
  CHECK(Camera(d, 4, 4).connect_problem().empty());
  d.camera_to_world = d.camera_to_world * scale({2, 2, 2});
  CHECK_THAT(Camera(d, 4, 4).connect_problem(), Catch::Contains("rotation and translation"));
}
