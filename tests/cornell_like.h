// A small closed diffuse Cornell-like box and the camera inside it, shared by the tests that compare an
// integrator against path tracing (test_igi.cc, test_lt.cc).
#pragma once
#include <memory>
#include <vector>

#include "camera/camera.h"
#include "geometry/mesh.h"
#include "scene/builder.h"

namespace torte::test {

inline std::shared_ptr<MaterialDesc> matte_rgb(Rgb albedo) {
  auto m = std::make_shared<MaterialDesc>();
  m->color.value = albedo;
  return m;
}

inline void add_quad(SceneBuilder& b, std::vector<Vec3f> points, std::shared_ptr<MaterialDesc> m, Rgb emission = Rgb(0)) {
  ShapeDesc s;
  s.kind = ShapeDesc::Kind::Mesh;
  s.mesh = std::make_shared<TriangleMesh>(make_polygon(points));
  s.material = std::move(m);
  s.emission = emission;
  b.add_shape(s);
}

// The box [-1, 1]^3, closed: white floor, ceiling, back and front walls, red left (+x) and green right (-x)
// walls, a white block on the floor and a square light just under the ceiling emitting downwards. The camera
// stands inside, near the front wall.
inline std::shared_ptr<Scene> cornell_like() {
  SceneBuilder b;
  const auto white = matte_rgb(Rgb(0.75f)), red = matte_rgb(Rgb(0.65f, 0.1f, 0.08f)), green = matte_rgb(Rgb(0.15f, 0.5f, 0.1f));
  add_quad(b, {{-1, -1, -1}, {1, -1, -1}, {1, -1, 1}, {-1, -1, 1}}, white);  // floor
  add_quad(b, {{-1, 1, -1}, {-1, 1, 1}, {1, 1, 1}, {1, 1, -1}}, white);      // ceiling
  add_quad(b, {{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}, white);      // back
  add_quad(b, {{-1, -1, -1}, {-1, 1, -1}, {1, 1, -1}, {1, -1, -1}}, white);  // front (behind the camera)
  add_quad(b, {{1, -1, -1}, {1, 1, -1}, {1, 1, 1}, {1, -1, 1}}, red);
  add_quad(b, {{-1, -1, -1}, {-1, -1, 1}, {-1, 1, 1}, {-1, 1, -1}}, green);
  ShapeDesc block;
  block.kind = ShapeDesc::Kind::Mesh;
  block.mesh = std::make_shared<TriangleMesh>(make_cube());
  block.transform = translate({0.35f, -0.6f, 0.3f}) * rotate(25, {0, 1, 0}) * scale({0.3f, 0.4f, 0.3f});
  block.material = white;
  b.add_shape(block);
  // Winding (p1 - p0) x (p2 - p0) = -y: emits downwards only.
  add_quad(b, {{-0.3f, 0.99f, -0.3f}, {0.3f, 0.99f, -0.3f}, {0.3f, 0.99f, 0.3f}, {-0.3f, 0.99f, 0.3f}},
           matte_rgb(Rgb(0)), Rgb(6));
  return b.flatten();
}

// The box seen from just inside its front wall.
inline CameraDesc box_camera() {
  CameraDesc c;
  c.camera_to_world = look_at({0, 0, -0.95f}, {0, 0, 1}, {0, 1, 0});
  c.fov_degrees = 75;
  return c;
}

}  // namespace torte::test
