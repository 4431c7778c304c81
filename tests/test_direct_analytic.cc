// Direct light from sphere lights against the closed form: a Lambert plane of albedo a under a sphere of
// radiance L, radius r, centre at distance d and height h over the shaded point (wholly above its horizon)
// reflects a L (r / d)^2 (h / d). Every camera integrator's next-event estimation, BSDF-sampled emitter hits and
// their MIS weights must add up to it; shadow rays towards the sphere must not be stopped by the sphere itself
// (a shadow ray kept along the unoffset direction lost up to four fifths of them).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "render/render.h"
#include "scene/builder.h"
#include "scene_helpers.h"

using namespace torte;
using namespace torte::test;

namespace {

struct SphereOverPlane {
  Vec3f centre;
  float radius;
  // The plane's radiance at the origin, seen by the probe camera.
  double expected(double albedo) const {
    const double d2 = double(length_squared(centre)), d = std::sqrt(d2);
    return albedo * double(radius) * double(radius) / d2 * (double(centre.y) / d);
  }
};

constexpr float kAlbedo = 0.6f;

// The plane y = 0 and the sphere light, plus a faint second sphere far away so that light selection has a
// choice to make.
std::shared_ptr<Scene> sphere_over_plane(const SphereOverPlane& g) {
  SceneBuilder b;
  ShapeDesc plane;
  plane.kind = ShapeDesc::Kind::Mesh;
  plane.mesh = std::make_shared<TriangleMesh>(make_polygon({{-8, 0, -8}, {-8, 0, 8}, {8, 0, 8}, {8, 0, -8}}));
  plane.material = matte(kAlbedo);
  b.add_shape(plane);
  ShapeDesc light = sphere_shape(g.radius, translate(g.centre), matte(0.2f));
  light.emission = Rgb(1);
  b.add_shape(light);
  ShapeDesc faint = sphere_shape(0.01f, translate({7, 5, 7}), matte(0.2f));
  faint.emission = Rgb(1e-7f);
  b.add_shape(faint);
  return b.flatten();
}

// Mean of a 4x4 image of the plane around the origin, from beside the sphere (a 0.5-degree view).
double probe(const Scene& scene, RenderSettings s) {
  s.width = s.height = 4;
  s.max_depth = 1;
  return image_mean(render_view(scene, camera_at({0, 0.3f, -0.3f}, {0, 0, 0}, 0.5f), s).image);
}

}  // namespace

TEST_CASE("Sphere lights over a plane: every camera integrator's direct light matches the closed form",
          "[light][render][analytic]") {
  const SphereOverPlane cases[] = {
      {{0, 0.4f, 0}, 0.2f},        // large and near: a 30-degree cone, most of it seen obliquely
      {{0.4f, 0.4f, 0.1f}, 0.04f},  // a small bead off to the side
      {{0.3f, 2, -0.2f}, 0.5f},     // far above
  };
  for (const SphereOverPlane& g : cases) {
    const auto scene = sphere_over_plane(g);
    const double expected = g.expected(kAlbedo);
    INFO("sphere at (" << g.centre.x << ", " << g.centre.y << ", " << g.centre.z << "), radius " << g.radius
                       << ": expected " << expected);
    const auto check = [&](const char* what, RenderSettings s, double tolerance) {
      INFO(what);
      CHECK(probe(*scene, s) == Approx(expected).epsilon(tolerance));
    };
    RenderSettings s;
    s.spp = 256;
    check("path, light BVH", s, 0.015);
    RenderSettings power = s;
    power.light_sampler = LightSamplerKind::Power;
    check("path, by power", power, 0.015);
    RenderSettings direct = s;
    direct.integrator = IntegratorKind::Direct;
    direct.sample_all_lights = true;
    check("direct, every light sampled", direct, 0.015);
    RenderSettings bdpt = s;
    bdpt.integrator = IntegratorKind::Bdpt;
    bdpt.spp = 1024;
    check("bdpt", bdpt, 0.02);
  }
}
