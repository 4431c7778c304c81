// Light tracing (render/integrator_lt.h) against path tracing: the small closed diffuse Cornell-like box (tile
// means of 16x16-pixel tiles of a 64x64 image), max_depth, a thin lens, white furnaces (a sphere under a uniform
// sky seen by an orthographic camera; inside an emitting sphere), determinism across thread counts (splats
// included) and the cameras it refuses.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "core/sampling.h"
#include "cornell_like.h"
#include "cornell_reference.h"
#include "render/render.h"
#include "scene_helpers.h"

using namespace torte;
using namespace torte::test;

TEST_CASE("lt converges to path on the Cornell-like box (16x16 tile means of a 64x64 image)", "[render][lt]") {
  const auto scene = cornell_like();
  const Image& path = path_reference();  // the suite's cached one
  const RenderOutput lt = render_view(*scene, box_camera(), integrator_settings(IntegratorKind::Lt, 64, 128));
  INFO("lt mean " << image_mean(lt.image) << ", path mean " << image_mean(path) << ", worst tile "
                  << max_tile_error(lt.image, path, 16));
  CHECK(image_mean(lt.image) == Approx(image_mean(path)).epsilon(0.01));
  // Measured over seeds: tile errors of about 1 % (one standard deviation) at 64 light paths per pixel.
  CHECK(max_tile_error(lt.image, path, 16) < 0.03);
  CHECK(lt.stats.samples_done == 64u * 64u * 128u);
  CHECK(lt.stats.shadow_rays > 0);
  CHECK(lt.stats.dropped_samples == 0);
}

TEST_CASE("lt equals path at max_depth 0, 1 and 2, and with a thin lens", "[render][lt]") {
  const auto scene = cornell_like();
  for (const int depth : {0, 1, 2}) {
    RenderSettings p = integrator_settings(IntegratorKind::Path, 32, 256), l = integrator_settings(IntegratorKind::Lt, 32, 64);
    p.max_depth = l.max_depth = depth;
    const Image path = render_view(*scene, box_camera(), p).image, lt = render_view(*scene, box_camera(), l).image;
    INFO("depth " << depth << ": lt " << image_mean(lt) << ", path " << image_mean(path) << ", worst tile "
                  << max_tile_error(lt, path, 16));
    if (depth == 0) {
      CHECK(lt.pixels == path.pixels);  // emitters seen directly: the same camera pass
    } else {
      CHECK(image_mean(lt) == Approx(image_mean(path)).epsilon(0.015));
      CHECK(max_tile_error(lt, path, 16) < 0.04);
    }
  }
  CameraDesc lens = box_camera();
  lens.aperture_radius = 0.05f;
  lens.focus_distance = 1.2f;
  const Image path = render_view(*scene, lens, integrator_settings(IntegratorKind::Path, 32, 256)).image;
  const Image lt = render_view(*scene, lens, integrator_settings(IntegratorKind::Lt, 32, 64)).image;
  INFO("thin lens: lt " << image_mean(lt) << ", path " << image_mean(path) << ", worst tile " << max_tile_error(lt, path, 16));
  CHECK(image_mean(lt) == Approx(image_mean(path)).epsilon(0.015));
  CHECK(max_tile_error(lt, path, 16) < 0.04);
}

TEST_CASE("lt furnace: a Lambert sphere under a uniform sky, orthographic camera, renders its albedo", "[render][lt][furnace]") {
  for (const float aperture : {0.0f, 0.1f}) {
    SceneBuilder b;
    b.add_shape(sphere_shape(1, Transform(), matte(0.6f)));
    b.add_light(uniform_sky(Rgb(1)));
    const auto scene = b.flatten();
    CameraDesc cam = furnace_camera();
    cam.aperture_radius = aperture;
    cam.focus_distance = 5;
    const Image img = render_view(*scene, cam, integrator_settings(IntegratorKind::Lt, 32, 64)).image;
    INFO("aperture " << aperture);
    CHECK(furnace_sphere_mean_green(img) == Approx(0.6).epsilon(0.02));
    if (aperture == 0) CHECK(img.at(0, 0).g == Approx(1.0f).epsilon(1e-5));  // the sky, from the camera pass
  }
}

TEST_CASE("lt furnace: inside a closed emitting Lambert sphere, depth k sees 1 - 0.8^(k+1)", "[render][lt][furnace]") {
  const auto scene = emitting_shell();
  for (const int depth : {1, 4}) {
    RenderSettings s = integrator_settings(IntegratorKind::Lt, 32, 64);
    s.max_depth = depth;
    s.rr_depth = 100;
    const Image img = render_view(*scene, shell_camera(), s).image;
    INFO("depth " << depth);
    CHECK(image_mean(img) == Approx(shell_radiance(depth)).epsilon(0.01));
  }
}

TEST_CASE("lt gives a bitwise identical image at 1 and 2 threads", "[render][lt][determinism]") {
  const auto scene = cornell_like();
  RenderSettings s = integrator_settings(IntegratorKind::Lt, 40, 4);
  s.height = 24;
  s.tile_size = 8;
  s.filter = Filter::mitchell();
  check_thread_determinism(*scene, box_camera(), s);
}

TEST_CASE("lt refuses a camera it cannot connect to; the other integrators accept it", "[render][lt]") {
  const auto scene = cornell_like();
  CameraDesc cam = box_camera();
  cam.camera_to_world = cam.camera_to_world * scale({1, 2, 1});
  RenderSettings s = integrator_settings(IntegratorKind::Lt, 8, 1);
  CHECK_THROWS_WITH(render_view(*scene, cam, s), Catch::Contains("integrator 'lt'") && Catch::Contains("rotation"));
  s.integrator = IntegratorKind::Path;
  CHECK_NOTHROW(render_view(*scene, cam, s));
}

TEST_CASE("lt interrupted mid-pass keeps its splats normalised by the light paths traced", "[render][lt]") {
  const auto scene = cornell_like();
  // Cancels once a third of the samples are done: in the middle of a pass, with tiles of it left undone.
  struct CancelAt : ProgressSink {
    std::atomic<bool>* cancel;
    explicit CancelAt(std::atomic<bool>* c) : cancel(c) {}
    void update(uint64_t done, uint64_t total, uint64_t, double) override {
      if (done * 3 >= total) cancel->store(true);
    }
  };
  const RenderSettings s = integrator_settings(IntegratorKind::Lt, 32, 64);
  std::atomic<bool> cancel{false};
  CancelAt sink(&cancel);
  const RenderOutput part = render(*scene, Camera(box_camera(), s.width, s.height), s, &sink, &cancel);
  const RenderOutput full = render_view(*scene, box_camera(), s);
  CHECK(part.stats.interrupted);
  CHECK(part.stats.samples_done < uint64_t(32 * 32 * 64));
  CHECK(part.stats.samples_done % uint64_t(16 * 16) == 0);  // whole tiles only
  INFO("interrupted mean " << image_mean(part.image) << ", full " << image_mean(full.image));
  CHECK(image_mean(part.image) == Approx(image_mean(full.image)).epsilon(0.03));
}

TEST_CASE("lt: shading normals get the adjoint correction (a coarse smooth-shaded sphere under a sky)", "[render][lt]") {
  // A 6 x 4 segment sphere with the exact sphere normals at its vertices: shading and geometric normals differ
  // by up to about 30 degrees, so light tracing matches path tracing only with the adjoint factor.
  TriangleMesh mesh;
  const int nu = 6, nv = 4;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const float theta = kPi * float(j) / nv, phi = 2 * kPi * float(i) / nu;
      const Vec3f p{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
      mesh.add_vertex(p);
      mesh.nx.push_back(p.x);
      mesh.ny.push_back(p.y);
      mesh.nz.push_back(p.z);
    }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const uint32_t a = uint32_t(j * (nu + 1) + i), b = a + 1, c = a + uint32_t(nu + 1), d = c + 1;
      if (j != 0) mesh.add_triangle(a, b, c);
      if (j != nv - 1) mesh.add_triangle(b, d, c);
    }
  SceneBuilder b;
  ShapeDesc s;
  s.kind = ShapeDesc::Kind::Mesh;
  s.mesh = std::make_shared<TriangleMesh>(mesh);
  s.material = matte(0.7f);
  b.add_shape(s);
  b.add_light(uniform_sky(Rgb(1)));
  const auto scene = b.flatten();
  CameraDesc cam = camera_at({0.5f, 2, -4}, {0, 0, 0}, 35);
  const Image path = render_view(*scene, cam, integrator_settings(IntegratorKind::Path, 32, 256)).image;
  const Image lt = render_view(*scene, cam, integrator_settings(IntegratorKind::Lt, 32, 256)).image;
  // The sphere's pixels only (the sky, at exactly 1, comes from the same camera pass in both).
  double sum_lt = 0, sum_path = 0;
  int n = 0;
  for (size_t k = 0; k < path.pixels.size(); ++k)
    if (path.pixels[k].average() < 0.9f) {
      sum_lt += lt.pixels[k].average();
      sum_path += path.pixels[k].average();
      ++n;
    }
  INFO("sphere pixels " << n << ": lt " << sum_lt / n << ", path " << sum_path / n);
  CHECK(n > 100);
  CHECK(sum_lt / n == Approx(sum_path / n).epsilon(0.01));
}
