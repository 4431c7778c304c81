// SceneBuilder: the mutable, object-like scene that Lua scripts fill. flatten() turns it into the immutable SoA
// Scene (meshes transformed to world space, materials gathered into per-type tables, lights resolved).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "scene/material_desc.h"
#include "scene/scene.h"
#include "voxel/voxel_shape.h"

namespace torte {

struct ShapeDesc {
  enum class Kind { Mesh, Quadric, Voxel } kind = Kind::Mesh;
  std::shared_ptr<const TriangleMesh> mesh;  // object space, shared between placements
  Quadric quadric;                           // object-space parameters; its transform is set at flatten
  std::shared_ptr<const VoxelShape> voxels;  // Kind::Voxel: the built grid and its id definitions (cell space)
  Transform transform;                       // object-to-world
  std::shared_ptr<const MaterialDesc> material;
  Rgb emission;            // diffuse area light radiance; black = not a light
  // Textured emission: `emission` times this colour texture at the surface point (meshes and quadrics).
  std::shared_ptr<const TextureDesc> emission_texture;
  bool two_sided = false;  // emit on both sides
  std::string origin;      // where the script made it ("torte.shape.mesh at scene.lua:7"), for messages; may be empty
};

class SceneBuilder;

// A placement of a group (a SceneBuilder used as a container of shapes and further placements).
struct InstanceDesc {
  std::shared_ptr<const SceneBuilder> group;
  Transform transform;  // group-to-parent
};

// A scene, or a group of shapes to place many times (instancing): the same type, so groups nest freely. Each
// placement of a group places a transformed copy of its point, spot and directional lights (placed_light);
// lights at infinity and emitting shapes belong to the scene that is rendered (area lights are not instanced).
//
// Groups nest at most kMaxGroupNesting levels, and the nesting places at most kMaxInstances instances and
// kMaxInstancedLights lights; flatten() counts them before it allocates anything.
class SceneBuilder {
 public:
  SceneBuilder() = default;
  // A copy has the same content, so it may keep the stamp; what is moved from gets a new one (it is emptied).
  SceneBuilder(const SceneBuilder&) = default;
  SceneBuilder& operator=(const SceneBuilder&) = default;
  SceneBuilder(SceneBuilder&& other) noexcept;
  SceneBuilder& operator=(SceneBuilder&& other) noexcept;
  // Releases chains of groups iteratively: a script can nest groups arbitrarily deep (flatten refuses them, the
  // destructor must still not recurse once per level).
  ~SceneBuilder();

  static constexpr int kMaxGroupNesting = 32;
  static constexpr uint64_t kMaxInstances = uint64_t(1) << 28;
  static constexpr uint64_t kMaxInstancedLights = uint64_t(1) << 20;

  void add_shape(ShapeDesc shape) {
    if (shape.kind == ShapeDesc::Kind::Voxel && shape.voxels)
      for (const auto& cell : shape.voxels->cells)
        if (cell.shapes) cell.shapes->placed_.value = true;
    shapes_.push_back(std::move(shape));
    restamp();
  }
  void add_instance(InstanceDesc instance) {
    if (instance.group) instance.group->placed_.value = true;
    instances_.push_back(std::move(instance));
    restamp();
  }
  void add_light(const Light& light) {
    lights_.push_back(light);
    restamp();
  }
  size_t shape_count() const { return shapes_.size(); }
  size_t light_count() const { return lights_.size(); }
  size_t instance_count() const { return instances_.size(); }

  // Throws torte::Error on invalid content (bad meshes, degenerate shapes, coordinates out of range after the
  // transforms, lights of non-finite power, too deep or too wide nesting), and torte::Interrupted when Ctrl-C
  // is pressed (core/interrupt.h). `progress` (optional): see Scene::finalize.
  // `options` (optional) replace accel_options() for this build (torte.render's keys).
  std::shared_ptr<Scene> flatten(ProgressCounter* progress = nullptr, const AccelOptions* options = nullptr) const;

  /// The triangles' layout options of torte.scene{...} (bvh_layout, memory_budget), which flatten() builds with.
  void set_accel_options(const AccelOptions& options) {
    accel_options_ = options;
    restamp();
  }
  const AccelOptions& accel_options() const { return accel_options_; }

  /// What flatten() reads, as stamps: this builder's, then those of the groups it places through instances and
  /// voxel cell shapes (depth first, each group once). Every change of a builder gives it a stamp never used
  /// before in the process, and all else a builder holds (meshes, materials, textures, voxel trees, lights) is
  /// immutable, so two equal fingerprints mean flatten() would build the same scene.
  std::vector<uint64_t> fingerprint() const;

  /// Whether this builder is `target` or places it, through instances and voxel cell shapes at any depth.
  /// scene:add refuses what would make a group place itself: such a cycle of shared owners would never be freed.
  bool reaches(const SceneBuilder* target) const;

 private:
  struct Flattening;
  static uint64_t new_stamp();
  void restamp() { stamp_ = new_stamp(); }
  std::vector<ShapeDesc> shapes_;
  std::vector<InstanceDesc> instances_;
  std::vector<Light> lights_;
  AccelOptions accel_options_;
  uint64_t stamp_ = new_stamp();
  // Whether some builder places this one (an instance or a voxel cell shape points at this object): a builder
  // nothing places cannot be reached from another, which lets reaches() answer without a walk. It belongs to the
  // object, not its content, so copies start unplaced and assignments keep their own.
  struct PlacedFlag {
    mutable bool value = false;
    PlacedFlag() = default;
    PlacedFlag(const PlacedFlag&) {}
    PlacedFlag& operator=(const PlacedFlag&) { return *this; }
  };
  PlacedFlag placed_;
};

}  // namespace torte
