// Direct light from area lights against closed forms, at the origin of a Lambert plane y = 0 of albedo a: under a
// sphere of radiance L, radius r, centre at distance d and height h (wholly above the horizon) the plane reflects
// a L (r / d)^2 (h / d); under a disk facing it from straight above, a L r^2 / (r^2 + h^2); under a polygon, a / pi
// times L times Lambert's contour integral of its vertices. Every camera integrator's next-event estimation,
// BSDF-sampled emitter hits and their MIS weights must add up to it, and shadow rays towards the light must not
// be stopped by the light itself (a shadow ray kept along the unoffset direction lost up to four fifths of a
// sphere's light).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "render/render.h"
#include "scene/builder.h"
#include "scene_helpers.h"

using namespace torte;
using namespace torte::test;

namespace {

constexpr float kAlbedo = 0.6f;
constexpr double kPiD = 3.14159265358979323846;

struct LitPlane {
  std::string name;
  std::vector<ShapeDesc> lights;  // each emitting radiance 1
  double expected;                // the plane's radiance at the origin
};

ShapeDesc emitting_sphere(Vec3f centre, float radius) {
  ShapeDesc light = sphere_shape(radius, translate(centre), matte(0.2f));
  light.emission = Rgb(1);
  return light;
}
double sphere_radiance(Vec3f centre, float radius) {
  const double d2 = double(length_squared(centre)), d = std::sqrt(d2);
  return kAlbedo * double(radius) * double(radius) / d2 * (double(centre.y) / d);
}

LitPlane sphere_case(Vec3f centre, float radius) {
  return {"sphere of radius " + std::to_string(radius) + " at height " + std::to_string(centre.y),
          {emitting_sphere(centre, radius)}, sphere_radiance(centre, radius)};
}

// Many lights for the light samplers to choose from: a 7 x 7 grid of small spheres 0.4 apart, all at height 0.5
// (so none hides another from the plane's origin), one straight above it.
LitPlane grid_case() {
  LitPlane c{"a grid of 49 small spheres", {}, 0};
  for (int i = -3; i <= 3; ++i)
    for (int j = -3; j <= 3; ++j) {
      const Vec3f centre(0.4f * float(i), 0.5f, 0.4f * float(j));
      c.lights.push_back(emitting_sphere(centre, 0.05f));
      c.expected += sphere_radiance(centre, 0.05f);
    }
  return c;
}

// A two-sided emitting disk of radius r facing the plane's origin from height h straight above it (sampled by
// area, as quadrics other than the sphere are): the plane reflects a L r^2 / (r^2 + h^2).
LitPlane disk_case(float radius, float height) {
  ShapeDesc light = sphere_shape(radius, translate({0, height, 0}) * rotate(90, {1, 0, 0}), matte(0.2f));
  light.quadric.kind = QuadricKind::Disk;
  light.emission = Rgb(1);
  light.two_sided = true;
  const double r2 = double(radius) * double(radius);
  return {"disk of radius " + std::to_string(radius) + " at height " + std::to_string(height), {light},
          kAlbedo * r2 / (r2 + double(height) * double(height))};
}

// A two-sided emitting polygon; the irradiance at the origin (normal +y) by Lambert's formula: half the sum, over
// the edges, of the angle each subtends times the y component of the unit normal of the plane through it and the
// origin.
LitPlane polygon_case(const char* name, const std::vector<Vec3f>& vertices) {
  ShapeDesc light;
  light.kind = ShapeDesc::Kind::Mesh;
  light.mesh = std::make_shared<TriangleMesh>(make_polygon(vertices));
  light.material = matte(0.2f);
  light.emission = Rgb(1);
  light.two_sided = true;
  double e = 0;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const Vec3f a = normalize(vertices[i]), b = normalize(vertices[(i + 1) % vertices.size()]);
    const double angle = std::acos(std::clamp(double(dot(a, b)), -1.0, 1.0));
    e += angle * double(normalize(cross(a, b)).y);
  }
  return {name, {light}, kAlbedo / kPiD * std::fabs(e) / 2};
}

// The plane and the light, plus a faint sphere far away so that light selection has a choice to make.
std::shared_ptr<Scene> lit_plane(const LitPlane& c) {
  SceneBuilder b;
  ShapeDesc plane;
  plane.kind = ShapeDesc::Kind::Mesh;
  plane.mesh = std::make_shared<TriangleMesh>(make_polygon({{-8, 0, -8}, {-8, 0, 8}, {8, 0, 8}, {8, 0, -8}}));
  plane.material = matte(kAlbedo);
  b.add_shape(plane);
  for (const ShapeDesc& light : c.lights) b.add_shape(light);
  ShapeDesc faint = sphere_shape(0.01f, translate({7, 5, 7}), matte(0.2f));
  faint.emission = Rgb(1e-7f);
  b.add_shape(faint);
  return b.flatten();
}

// Mean of a 4x4 image of the plane around the origin, from beside the light (a 0.5-degree view).
double probe(const Scene& scene, RenderSettings s) {
  s.width = s.height = 4;
  s.max_depth = 1;
  return image_mean(render_view(scene, camera_at({0, 0.3f, -0.3f}, {0, 0, 0}, 0.5f), s).image);
}

}  // namespace

TEST_CASE("Area lights over a plane: every camera integrator's direct light matches the closed form",
          "[light][render][analytic]") {
  const LitPlane cases[] = {
      sphere_case({0, 0.4f, 0}, 0.2f),          // large and near: a 30-degree cone, most of it seen obliquely
      sphere_case({0.4f, 0.4f, 0.1f}, 0.04f),   // a small bead off to the side
      sphere_case({0.3f, 2, -0.2f}, 0.5f),      // far above
      grid_case(),
      disk_case(0.3f, 0.5f),
      polygon_case("square above", {{-0.3f, 0.5f, -0.3f}, {0.3f, 0.5f, -0.3f}, {0.3f, 0.5f, 0.3f}, {-0.3f, 0.5f, 0.3f}}),
      polygon_case("steep quad beside", {{0.3f, 0.02f, 0.4f}, {0.3f, 0.02f, 0.9f}, {0.5f, 0.6f, 0.9f}, {0.5f, 0.6f, 0.4f}}),
  };
  for (const LitPlane& c : cases) {
    const auto scene = lit_plane(c);
    INFO(c.name << ": expected " << c.expected);
    const auto check = [&](const char* what, RenderSettings s, double tolerance) {
      INFO(what);
      CHECK(probe(*scene, s) == Approx(c.expected).epsilon(tolerance));
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
