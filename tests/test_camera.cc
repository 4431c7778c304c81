// Cameras: the thin-lens camera against the pinhole and orthographic cameras it generalises (aperture 0 gives
// the same rays), its focus plane, and a small render where a focused edge stays sharp and a defocused one blurs.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "camera/camera.h"
#include "core/rng.h"
#include "film/image.h"
#include "render/render.h"
#include "scene/builder.h"
#include "scene_helpers.h"
#include "test_random.h"

using namespace torte;
using namespace torte::test;
using torte::test::next_2d;

TEST_CASE("Thin lens: aperture 0 is the pinhole; rays meet on the focus plane", "[camera]") {
  for (const CameraKind kind : {CameraKind::Perspective, CameraKind::Orthographic}) {
    CameraDesc d;
    d.kind = kind;
    d.camera_to_world = look_at({1, 2, -4}, {0, 0.5f, 0}, {0, 1, 0});
    d.fov_degrees = 50;
    d.extent = 3;
    const Camera pin(d, 40, 30);
    d.focus_distance = 3;
    const Camera zero(d, 40, 30);
    d.aperture_radius = 0.2f;
    const Camera lens(d, 40, 30);
    Pcg32 rng(2);
    const Vec3f axis = d.camera_to_world.apply_vector({0, 0, 1});
    for (int i = 0; i < 200; ++i) {
      const Vec2f raster(rng.next_float() * 40, rng.next_float() * 30);
      const Vec2f u = next_2d(rng);
      const Ray a = pin.generate_ray(raster), b = zero.generate_ray(raster, u);
      REQUIRE(a.o == b.o);
      REQUIRE(a.d == b.d);
      // The lens ray and the pinhole ray meet where the pinhole ray crosses the plane in focus.
      const Ray c = lens.generate_ray(raster, u);
      const Vec3f eye = pin.generate_ray({20, 15}).o;
      const Vec3f target = a.o + a.d * ((3 - dot(a.o - eye, axis)) / dot(a.d, axis));
      const Vec3f on_c = c.o + c.d * ((3 - dot(c.o - eye, axis)) / dot(c.d, axis));
      CHECK(length(target - on_c) < 1e-4f);
      CHECK(std::fabs(length(c.d) - 1) < 1e-5f);
      CHECK(length(c.o - a.o) <= 0.2f * 1.0001f);
    }
  }
  CameraDesc bad;
  bad.aperture_radius = -1;
  CHECK_THROWS(Camera(bad, 4, 4));
}

TEST_CASE("Thin lens renders: aperture 0 equals the pinhole image, focused edge stays sharp", "[camera][render]") {
  // An emitting wall with a vertical edge at distance 4 in front of the camera, on a black background.
  auto image = [](float aperture, float focus) {
    SceneBuilder b;
    ShapeDesc wall;
    wall.kind = ShapeDesc::Kind::Mesh;
    wall.mesh = std::make_shared<TriangleMesh>(make_polygon({{0, -3, 4}, {0, 3, 4}, {-5, 3, 4}, {-5, -3, 4}}));
    wall.material = matte(0);
    wall.emission = Rgb(1);
    wall.two_sided = true;
    b.add_shape(wall);
    CameraDesc cam;
    cam.camera_to_world = look_at({0, 0, 0}, {0, 0, 1}, {0, 1, 0});
    cam.fov_degrees = 30;
    cam.aperture_radius = aperture;
    cam.focus_distance = focus;
    const auto scene = b.flatten();
    RenderSettings s;
    s.width = 32;
    s.height = 8;
    s.spp = 64;
    s.max_depth = 1;
    return render_view(*scene, cam, s).image;
  };
  auto column = [](const Image& img, int x) {
    double sum = 0;
    for (int y = 0; y < img.height; ++y) sum += img.at(x, y).g;
    return sum / img.height;
  };
  const Image pin = image(0, 1), zero = image(0, 4), sharp = image(0.5f, 4), blurred = image(0.5f, 1.5f);
  CHECK(pin.pixels == zero.pixels);
  // The wall (world x < 0: the image's right half, columns 16..31) keeps its sharp edge when in focus.
  for (int x = 0; x < 32; ++x) CHECK(column(sharp, x) == Approx(column(pin, x)).margin(0.03));
  CHECK(column(pin, 15) == 0);
  CHECK(column(pin, 16) == Approx(1));
  // Out of focus (a blur radius of about two pixels), the columns next to the edge mix.
  CHECK(column(blurred, 15) > 0.1);
  CHECK(column(blurred, 16) < 0.9);
}
