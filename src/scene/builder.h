// SceneBuilder: the mutable, object-like scene that Lua scripts fill. flatten() turns it into the immutable SoA
// Scene (meshes transformed to world space, materials gathered into per-type tables, lights resolved).
#pragma once
#include <memory>
#include <vector>

#include "scene/scene.h"

namespace torte {

struct MaterialDesc {
  MaterialType type = MaterialType::Lambert;
  LambertParams lambert;
};

struct ShapeDesc {
  enum class Kind { Mesh, Quadric } kind = Kind::Mesh;
  std::shared_ptr<const TriangleMesh> mesh;  // object space, shared between placements
  Quadric quadric;                           // object-space parameters; its transform is set at flatten
  Transform transform;                       // object-to-world
  std::shared_ptr<const MaterialDesc> material;
  Rgb emission;            // diffuse area light radiance; black = not a light
  bool two_sided = false;  // emit on both sides
};

class SceneBuilder {
 public:
  void add_shape(ShapeDesc shape) { shapes_.push_back(std::move(shape)); }
  void add_light(const Light& light) { lights_.push_back(light); }
  void set_camera(const CameraDesc& camera) { camera_ = camera; has_camera_ = true; }
  size_t shape_count() const { return shapes_.size(); }
  size_t light_count() const { return lights_.size(); }

  // Throws torte::Error on invalid content (bad meshes, degenerate shapes).
  std::shared_ptr<Scene> flatten() const;

 private:
  std::vector<ShapeDesc> shapes_;
  std::vector<Light> lights_;
  CameraDesc camera_;
  bool has_camera_ = false;
};

}  // namespace torte
