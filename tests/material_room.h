// The test scene shared by tests/test_wavefront_vs_reference.cc and bench/bench_shading.cc: a closed room lit by
// a spherical lamp, a ceiling panel and a point light, holding one sphere per material type (Lambert walls,
// Oren-Nayar, mirror, rough gold, plastic, glass) and a Lambert block. Materials are built as MaterialDesc
// directly; roughness values go through the default remap alpha = r^2.
#pragma once
#include <memory>

#include "camera/camera.h"
#include "scene/builder.h"

namespace torte::test {

namespace room_detail {
inline std::shared_ptr<MaterialDesc> material(MaterialType type, Rgb color) {
  auto m = std::make_shared<MaterialDesc>();
  m->type = type;
  m->color.value = color;
  return m;
}

inline ShapeDesc sphere(float radius, Vec3f center, std::shared_ptr<MaterialDesc> m) {
  ShapeDesc s;
  s.kind = ShapeDesc::Kind::Quadric;
  s.quadric.kind = QuadricKind::Sphere;
  s.quadric.radius = radius;
  s.transform = translate(center);
  s.material = std::move(m);
  return s;
}

}  // namespace room_detail

inline std::shared_ptr<Scene> material_room() {
  using namespace room_detail;
  SceneBuilder b;
  ShapeDesc room;
  room.kind = ShapeDesc::Kind::Mesh;
  room.mesh = std::make_shared<TriangleMesh>(make_cube());
  room.transform = scale({2, 1.5f, 2});
  room.material = material(MaterialType::Lambert, Rgb(0.6f, 0.55f, 0.5f));
  b.add_shape(room);

  auto oren_nayar = material(MaterialType::OrenNayar, Rgb(0.7f, 0.6f, 0.4f));
  oren_nayar->sigma.value = 30;  // degrees
  auto mirror = material(MaterialType::Mirror, Rgb(0.9f));
  auto metal = material(MaterialType::Conductor, Rgb(1));
  metal->eta_rgb.value = Rgb(0.143f, 0.374f, 1.442f);  // gold
  metal->k.value = Rgb(3.983f, 2.385f, 1.603f);
  metal->roughness.u.value = 0.5f;  // alpha = 0.25
  metal->roughness.v.value = 0.5f;
  auto glass = material(MaterialType::Dielectric, Rgb(1));
  glass->eta.value = 1.5f;
  auto plastic = material(MaterialType::CoatedDiffuse, Rgb(0.2f, 0.4f, 0.7f));
  plastic->eta.value = 1.5f;
  plastic->roughness.u.value = 0.3f;
  plastic->roughness.v.value = 0.3f;

  b.add_shape(sphere(0.35f, {-1.2f, -1.15f, 0.4f}, oren_nayar));
  b.add_shape(sphere(0.35f, {-0.4f, -1.15f, 0.6f}, mirror));
  b.add_shape(sphere(0.35f, {0.4f, -1.15f, 0.6f}, metal));
  b.add_shape(sphere(0.35f, {1.2f, -1.15f, 0.4f}, plastic));
  b.add_shape(sphere(0.3f, {0.0f, -1.2f, -0.5f}, glass));
  ShapeDesc block = room;
  block.transform = translate({-0.9f, -1.3f, -0.6f}) * rotate(30, {0, 1, 0}) * scale({0.2f, 0.2f, 0.2f});
  block.material = material(MaterialType::Lambert, Rgb(0.3f, 0.6f, 0.3f));
  b.add_shape(block);

  ShapeDesc lamp = sphere(0.15f, {0.5f, 1.0f, 0.5f}, material(MaterialType::Lambert, Rgb(0)));
  lamp.emission = Rgb(20, 15, 10);
  b.add_shape(lamp);
  ShapeDesc panel;
  panel.kind = ShapeDesc::Kind::Mesh;
  panel.mesh = std::make_shared<TriangleMesh>(
      make_polygon({{-1, 1.45f, -1}, {-0.3f, 1.45f, -1}, {-0.3f, 1.45f, -0.3f}, {-1, 1.45f, -0.3f}}));
  panel.material = material(MaterialType::Lambert, Rgb(0));
  panel.emission = Rgb(4);
  panel.two_sided = true;
  b.add_shape(panel);
  Light point;
  point.kind = LightKind::Point;
  point.position = {1.2f, 0.5f, -1.2f};
  point.radiance = Rgb(1.5f);
  b.add_light(point);

  return b.flatten();
}

// The view of the room the tests and the shading benchmark render.
inline CameraDesc material_room_camera() {
  CameraDesc cam;
  cam.camera_to_world = look_at({0, -0.2f, -1.9f}, {0, -0.9f, 0.3f}, {0, 1, 0});
  cam.fov_degrees = 65;
  return cam;
}

}  // namespace torte::test
