#include "scene/builder.h"

#include <map>

#include "core/error.h"

namespace torte {

// State shared while one scene is flattened: materials and textures go to the scene's tables once each, every
// group with shapes becomes one prototype, and every path through the nesting of groups one instance.
struct SceneBuilder::Flattening {
  Scene& scene;
  TextureTableBuilder textures;
  MaterialFlattener materials;
  std::map<const SceneBuilder*, uint32_t> prototype_of;
  // Objects are numbered scene shapes first, then prototype after prototype: collected per prototype here and
  // appended once the scene's own shapes are known.
  std::vector<std::vector<SceneObject>> prototype_objects;

  explicit Flattening(Scene& s) : scene(s), materials(s.materials, textures) {}

  MaterialRef material(const std::shared_ptr<const MaterialDesc>& m) {
    static const MaterialDesc kDefault{};
    return materials.add(m ? *m : kDefault);
  }

  // Meshes come first in a set's object numbering, then quadrics (see GeometrySet).
  static std::vector<const ShapeDesc*> ordered(const std::vector<ShapeDesc>& shapes) {
    std::vector<const ShapeDesc*> out;
    for (const ShapeDesc& s : shapes)
      if (s.kind == ShapeDesc::Kind::Mesh) out.push_back(&s);
    for (const ShapeDesc& s : shapes)
      if (s.kind == ShapeDesc::Kind::Quadric) out.push_back(&s);
    for (const ShapeDesc& s : shapes)
      if (s.kind == ShapeDesc::Kind::Voxel) out.push_back(&s);
    return out;
  }

  // A voxel grid's accelerator: materials of its ids go to the scene's override table, cell shapes become
  // GeometrySets in unit-cell space.
  VoxelGridAccel voxel_grid(const ShapeDesc& s) {
    if (!s.voxels || !s.voxels->tree) throw Error("internal: voxel shape without a grid");
    if (!s.emission.is_black())
      throw Error("voxel grids cannot be area lights; give the emitting ids an emissive look instead");
    const VoxelShape& v = *s.voxels;
    VoxelGridAccel g;
    g.tree = v.tree;
    g.to_set = s.transform;
    int lo = 0, hi = -1;
    for (const VoxelCubeDef& c : v.cubes) {
      lo = hi < lo ? c.id : std::min(lo, int(c.id));
      hi = std::max(hi, int(c.id));
    }
    if (hi >= lo) {
      g.id_lo = lo;
      g.face_material.assign(size_t(hi - lo + 1) * 6, -1);
      for (const VoxelCubeDef& c : v.cubes)
        for (int f = 0; f < 6; ++f) {
          if (!c.faces[size_t(f)]) continue;
          g.face_material[size_t(c.id - lo) * 6 + size_t(f)] = int32_t(scene.material_overrides.size());
          scene.material_overrides.push_back(material(c.faces[size_t(f)]));
        }
    }
    for (const VoxelCellDef& c : v.cells) {
      if (!c.shapes) continue;
      if (!c.shapes->instances_.empty() || !c.shapes->lights_.empty())
        throw Error("voxel cell shape " + std::to_string(c.id) + ": the group may hold shapes only (no instances, lights)");
      auto cell = std::make_shared<VoxelCellGeometry>();
      for (const ShapeDesc* sh : ordered(c.shapes->shapes_)) {
        if (sh->kind == ShapeDesc::Kind::Voxel) throw Error("voxel cell shapes cannot hold voxel grids");
        if (!sh->emission.is_black()) throw Error("voxel cell shapes cannot emit (area lights are not instanced)");
        place(*sh, cell->meshes, cell->quadrics);
        cell->object_material.push_back(int32_t(scene.material_overrides.size()));
        scene.material_overrides.push_back(material(sh->material));
      }
      cell->build();
      const size_t k = size_t(-int(c.id));
      if (g.cells.size() <= k) g.cells.resize(k + 1);
      g.cells[k] = std::move(cell);
    }
    return g;
  }

  static void place(const ShapeDesc& s, std::vector<TriangleMesh>& meshes, std::vector<Quadric>& quadrics) {
    if (s.kind == ShapeDesc::Kind::Mesh) {
      TriangleMesh mesh = *s.mesh;
      mesh.transform(s.transform);
      meshes.push_back(std::move(mesh));
    } else {
      Quadric q = s.quadric;
      q.to_world = s.transform;
      quadrics.push_back(q);
    }
  }

  uint32_t prototype(const SceneBuilder& group) {
    if (auto it = prototype_of.find(&group); it != prototype_of.end()) return it->second;
    if (!group.lights_.empty()) throw Error("a group placed as an instance holds lights; add lights to the scene");
    auto proto = std::make_unique<Prototype>();
    std::vector<SceneObject> objects;
    for (const ShapeDesc* s : ordered(group.shapes_)) {
      if (!s->emission.is_black())
        throw Error("a group placed as an instance holds an emitting shape; area lights cannot be instanced, add "
                    "the emitter to the scene itself");
      if (s->kind == ShapeDesc::Kind::Voxel)
        proto->grids.push_back(voxel_grid(*s));
      else
        place(*s, proto->meshes, proto->quadrics);
      objects.push_back({material(s->material), -1});
    }
    const uint32_t index = uint32_t(scene.prototypes.size());
    scene.prototypes.push_back(std::move(proto));
    prototype_objects.push_back(std::move(objects));
    prototype_of.emplace(&group, index);
    return index;
  }

  // One instance per path through the nesting; `to_world` places `group`'s contents.
  void instantiate(const SceneBuilder& group, const Transform& to_world, int depth) {
    if (depth > 32) throw Error("groups nest more than 32 levels deep (does a group contain itself?)");
    if (!group.shapes_.empty()) {
      if (scene.instances.size() >= (size_t(1) << 28)) throw Error("more than 2^28 instances after nesting");
      scene.instances.push_back({to_world, prototype(group)});
    }
    for (const InstanceDesc& inst : group.instances_) {
      if (!inst.group) throw Error("internal: instance without a group");
      instantiate(*inst.group, to_world * inst.transform, depth + 1);
    }
  }
};

std::shared_ptr<Scene> SceneBuilder::flatten() const {
  auto scene = std::make_shared<Scene>();
  Flattening f(*scene);

  for (const ShapeDesc* s : Flattening::ordered(shapes_)) {
    const uint32_t object = uint32_t(scene->objects.size());
    if (s->kind == ShapeDesc::Kind::Voxel) {
      scene->grids.push_back(f.voxel_grid(*s));
      scene->objects.push_back({f.material(s->material), -1});
      continue;
    }
    Flattening::place(*s, scene->meshes, scene->quadrics);
    SceneObject obj;
    obj.material = f.material(s->material);
    if (!s->emission.is_black()) {
      Light light;
      light.kind = LightKind::Area;
      light.radiance = s->emission;
      light.object = object;
      light.two_sided = s->two_sided;
      obj.area_light = int32_t(scene->lights.size());
      scene->lights.push_back(light);
    }
    scene->objects.push_back(obj);
  }
  for (const InstanceDesc& inst : instances_) {
    if (!inst.group) throw Error("internal: instance without a group");
    f.instantiate(*inst.group, inst.transform, 1);
  }
  for (const auto& objects : f.prototype_objects)
    scene->objects.insert(scene->objects.end(), objects.begin(), objects.end());

  for (const Light& l : lights_) scene->lights.push_back(l);
  scene->textures = f.textures.finish();
  scene->camera = camera_;
  scene->has_camera = has_camera_;
  scene->finalize();
  return scene;
}

}  // namespace torte
