// Small scene-building helpers shared by the renderer tests (SceneBuilder descriptions, not Lua).
#pragma once
#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "render/render.h"
#include "scene/builder.h"

namespace torte::test {

// A Lambert material of grey albedo.
inline std::shared_ptr<MaterialDesc> matte(float albedo) {
  auto m = std::make_shared<MaterialDesc>();
  m->color.value = Rgb(albedo);
  return m;
}

// An infinite light of one radiance from every direction (a uniform sky).
inline Light uniform_sky(Rgb radiance) {
  Light sky;
  sky.kind = LightKind::Infinite;
  sky.radiance = radiance;
  return sky;
}

// A quadric sphere of `radius` placed by `t`.
inline ShapeDesc sphere_shape(float radius, const Transform& t, std::shared_ptr<MaterialDesc> m) {
  ShapeDesc s;
  s.kind = ShapeDesc::Kind::Quadric;
  s.quadric.kind = QuadricKind::Sphere;
  s.quadric.radius = radius;
  s.transform = t;
  s.material = std::move(m);
  return s;
}

// A perspective camera at `eye` looking at `target`, +y up, vertical field of view `fov` degrees.
inline CameraDesc camera_at(Vec3f eye, Vec3f target, float fov) {
  CameraDesc c;
  c.camera_to_world = look_at(eye, target, {0, 1, 0});
  c.fov_degrees = fov;
  return c;
}

// The furnace view: an orthographic camera on -z looking at the origin, 2.5 units across, so a unit sphere at
// the origin fills the middle of the image with background in the corners.
inline CameraDesc furnace_camera() {
  CameraDesc c;
  c.kind = CameraKind::Orthographic;
  c.camera_to_world = look_at({0, 0, -5}, {0, 0, 0}, {0, 1, 0});
  c.extent = 2.5f;
  return c;
}

// The mean of channel(pixel) over the pixels of a furnace_camera image that lie well inside a unit sphere's
// silhouette (x^2 + y^2 < 0.8 on the 2.5-unit view), away from its antialiased rim.
template <class Channel>
double furnace_sphere_mean(const Image& img, Channel&& channel) {
  double sum = 0;
  int n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const float px = (x + 0.5f) / img.width * 2.5f - 1.25f, py = (y + 0.5f) / img.height * 2.5f - 1.25f;
      if (px * px + py * py < 0.8f) {
        sum += channel(img.at(x, y));
        ++n;
      }
    }
  return sum / n;
}
inline double furnace_sphere_mean_green(const Image& img) {
  return furnace_sphere_mean(img, [](const Rgb& c) { return double(c.g); });
}

// The furnace of the integrator tests: inside a closed two-sided sphere of albedo 0.8 emitting 0.2, a path of
// at most `depth` scattering events sees 1 - 0.8^(depth + 1) (the geometric series of emission and reflection).
inline std::shared_ptr<Scene> emitting_shell() {
  SceneBuilder b;
  ShapeDesc shell = sphere_shape(1, Transform(), matte(0.8f));
  shell.emission = Rgb(0.2f);
  shell.two_sided = true;
  b.add_shape(shell);
  return b.flatten();
}
inline CameraDesc shell_camera() { return camera_at({0.2f, -0.1f, 0.3f}, {0, 0, 1}, 60); }
inline double shell_radiance(int depth) { return 1 - std::pow(0.8, depth + 1); }

// render() as `camera` sees the scene: the Camera is made for the settings' image size.
inline RenderOutput render_view(const Scene& scene, const CameraDesc& camera, const RenderSettings& s,
                                const std::atomic<bool>* cancel = nullptr) {
  return render(scene, Camera(camera, s.width, s.height), s, nullptr, cancel);
}

// Mean colour of the pixels [x0, x1) x [y0, y1).
inline Rgb tile_mean(const Image& img, int x0, int y0, int x1, int y1) {
  Rgb sum(0);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += img.at(x, y);
  return sum * (1.0f / float((x1 - x0) * (y1 - y0)));
}

// Settings of a square render of `size` pixels at `spp` with integrator `k` (16-pixel tiles).
inline RenderSettings integrator_settings(IntegratorKind k, int size, int spp) {
  RenderSettings s;
  s.width = s.height = size;
  s.spp = spp;
  s.integrator = k;
  s.tile_size = 16;
  return s;
}

// Channel-averaged means of the image's `tile` x `tile` tiles, row by row.
inline std::vector<double> tile_means(const Image& img, int tile) {
  std::vector<double> out;
  for (int y0 = 0; y0 < img.height; y0 += tile)
    for (int x0 = 0; x0 < img.width; x0 += tile) out.push_back(tile_mean(img, x0, y0, x0 + tile, y0 + tile).average());
  return out;
}

inline double image_mean(const Image& img) { return tile_mean(img, 0, 0, img.width, img.height).average(); }

// Largest relative difference of a tile mean of `a` from the same tile of `reference`.
inline double max_tile_error(const Image& a, const Image& reference, int tile) {
  const auto ta = tile_means(a, tile), tr = tile_means(reference, tile);
  double worst = 0;
  for (size_t t = 0; t < ta.size(); ++t) worst = std::max(worst, std::fabs(ta[t] - tr[t]) / tr[t]);
  return worst;
}

// The image must not depend on the thread count (bitwise), and must depend on the seed.
inline void check_thread_determinism(const Scene& scene, const CameraDesc& camera, RenderSettings s) {
  Image one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = render_view(scene, camera, s).image;
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = render_view(scene, camera, s).image;
  }
  REQUIRE(one.pixels.size() == two.pixels.size());
  CHECK(std::memcmp(one.pixels.data(), two.pixels.data(), one.pixels.size() * sizeof(Rgb)) == 0);
  s.seed += 1;
  const Image other = render_view(scene, camera, s).image;
  CHECK(std::memcmp(one.pixels.data(), other.pixels.data(), one.pixels.size() * sizeof(Rgb)) != 0);
}

}  // namespace torte::test
