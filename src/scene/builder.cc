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
  // GeometrySets in unit-cell space. Emitting ids become one Patches light (only for grids the scene holds
  // itself, `can_emit`: area lights are not instanced).
  VoxelGridAccel voxel_grid(const ShapeDesc& s, bool can_emit) {
    if (!s.voxels || !s.voxels->tree) throw Error("internal: voxel shape without a grid");
    if (!s.emission.is_black())
      throw Error("voxel grids cannot be area lights as a whole; give the emitting ids an emission (define{emission=...})");
    const VoxelShape& v = *s.voxels;
    VoxelGridAccel g;
    g.tree = v.tree;
    g.to_set = s.transform;
    int lo = 0, hi = -1;
    for (const VoxelCubeDef& c : v.cubes) {
      lo = hi < lo ? c.id : std::min(lo, int(c.id));
      hi = std::max(hi, int(c.id));
    }
    VoxelEmitters emitters;
    if (hi >= lo) {
      g.id_lo = lo;
      g.face_material.assign(size_t(hi - lo + 1) * 6, -1);
      for (const VoxelCubeDef& c : v.cubes) {
        const bool emits = !c.emission.is_black();
        if (emits) emitters.cubes.emplace(c.id, c.emission);
        for (int f = 0; f < 6; ++f) {
          // An emitting face needs an override entry of its own to carry its emission.
          if (!c.faces[size_t(f)] && !emits) continue;
          const int32_t k = int32_t(scene.material_overrides.size());
          g.face_material[size_t(c.id - lo) * 6 + size_t(f)] = k;
          scene.material_overrides.push_back(material(c.faces[size_t(f)] ? c.faces[size_t(f)] : s.material));
          if (emits) emitters.overrides.push_back({k, c.emission, false});
        }
      }
    }
    for (const VoxelCellDef& c : v.cells) {
      if (!c.shapes) continue;
      if (!c.shapes->instances_.empty() || !c.shapes->lights_.empty())
        throw Error("voxel cell shape " + std::to_string(c.id) + ": the group may hold shapes only (no instances, lights)");
      auto cell = std::make_shared<VoxelCellGeometry>();
      for (const ShapeDesc* sh : ordered(c.shapes->shapes_)) {
        if (sh->kind == ShapeDesc::Kind::Voxel) throw Error("voxel cell shapes cannot hold voxel grids");
        const bool emits = !sh->emission.is_black();
        if (emits && sh->kind != ShapeDesc::Kind::Mesh)
          throw Error("voxel cell shape " + std::to_string(c.id) +
                      ": only meshes (polygons, cubes, meshes) can emit inside a voxel cell, not analytic shapes");
        place(*sh, cell->meshes, cell->quadrics);
        const int32_t k = int32_t(scene.material_overrides.size());
        cell->object_material.push_back(k);
        scene.material_overrides.push_back(material(sh->material));
        if (emits) {
          emitters.cells[c.id].push_back({cell->meshes.size() - 1, sh->emission});
          emitters.overrides.push_back({k, sh->emission, true});
        }
      }
      cell->build();
      const size_t k = size_t(-int(c.id));
      if (g.cells.size() <= k) g.cells.resize(k + 1);
      g.cells[k] = std::move(cell);
    }
    if (!emitters.overrides.empty()) {
      if (!can_emit)
        throw Error("a voxel grid placed in a group has emitting ids; area lights cannot be instanced, add the grid "
                    "to the scene itself");
      add_voxel_light(g, emitters);
    }
    return g;
  }

  // What emits in one grid: cube ids, the emitting meshes of cell ids, and the override entries to mark.
  struct VoxelEmitters {
    struct Override {
      int32_t index;
      Rgb radiance;
      bool two_sided;
    };
    struct CellMesh {
      size_t mesh;
      Rgb radiance;
    };
    std::map<int16_t, Rgb> cubes;
    std::map<int16_t, std::vector<CellMesh>> cells;
    std::vector<Override> overrides;
  };

  // Gathers the exposed faces of emitting cubes (a face whose neighbour is not a solid cube) and the triangles of
  // emitting cell meshes into one Patches light, in world space.
  void add_voxel_light(const VoxelGridAccel& g, const VoxelEmitters& e) {
    auto patches = std::make_shared<EmissivePatches>();
    const VoxelTree& tree = *g.tree;
    const Transform& T = g.to_set;
    tree.for_each_leaf([&](const int lo[3], const int size[3], int16_t id) {
      if (id > 0) {
        const auto it = e.cubes.find(id);
        if (it == e.cubes.end()) return;
        for (int x = lo[0]; x < lo[0] + size[0]; ++x)
          for (int y = lo[1]; y < lo[1] + size[1]; ++y)
            for (int z = lo[2]; z < lo[2] + size[2]; ++z) {
              const int v[3] = {x, y, z};
              for (int face = 0; face < 6; ++face) {
                const int a = face / 2, step = face % 2 == 0 ? 1 : -1;
                int nb[3] = {x, y, z};
                nb[a] += step;
                // Inside the leaf the neighbour is the same solid id; outside, ask the tree.
                if (nb[a] >= lo[a] && nb[a] < lo[a] + size[a]) continue;
                if (tree.lookup(nb[0], nb[1], nb[2]) > 0) continue;
                Vec3f corner{float(v[0]), float(v[1]), float(v[2])};
                corner[a] += step > 0 ? 1.0f : 0.0f;
                Vec3f e1(0, 0, 0), e2(0, 0, 0), n(0, 0, 0);
                e1[voxel_face_u_axis(a)] = 1;
                e2[voxel_face_v_axis(a)] = 1;
                n[a] = float(step);
                patches->add_parallelogram(T.apply_point(corner), T.apply_vector(e1), T.apply_vector(e2),
                                           normalize(T.apply_normal(n)), it->second, false);
              }
            }
      } else {
        const auto it = e.cells.find(id);
        if (it == e.cells.end()) return;
        const VoxelCellGeometry& cell = *g.cell(id);
        for (int x = lo[0]; x < lo[0] + size[0]; ++x)
          for (int y = lo[1]; y < lo[1] + size[1]; ++y)
            for (int z = lo[2]; z < lo[2] + size[2]; ++z) {
              const Vec3f offset{float(x), float(y), float(z)};
              for (const VoxelEmitters::CellMesh& cm : it->second) {
                const TriangleMesh& mesh = cell.meshes[cm.mesh];
                for (size_t t = 0; t < mesh.triangle_count(); ++t) {
                  const uint32_t* idx = &mesh.indices[3 * t];
                  patches->add_triangle(T.apply_point(mesh.position(idx[0]) + offset),
                                        T.apply_point(mesh.position(idx[1]) + offset),
                                        T.apply_point(mesh.position(idx[2]) + offset), cm.radiance, true);
                }
              }
            }
      }
    });
    if (patches->size() == 0) return;  // every emitter is buried: nothing to see or sample
    patches->finish();
    Light light;
    light.kind = LightKind::Patches;
    light.patches = patches;
    const int32_t light_index = int32_t(scene.lights.size());
    scene.lights.push_back(light);
    if (scene.override_emission.size() < scene.material_overrides.size())
      scene.override_emission.resize(scene.material_overrides.size());
    for (const VoxelEmitters::Override& o : e.overrides)
      scene.override_emission[size_t(o.index)] = {o.radiance, light_index, o.two_sided};
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
        proto->grids.push_back(voxel_grid(*s, false));
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

std::shared_ptr<Scene> SceneBuilder::flatten(ProgressCounter* progress) const {
  auto scene = std::make_shared<Scene>();
  Flattening f(*scene);

  for (const ShapeDesc* s : Flattening::ordered(shapes_)) {
    const uint32_t object = uint32_t(scene->objects.size());
    if (s->kind == ShapeDesc::Kind::Voxel) {
      scene->grids.push_back(f.voxel_grid(*s, true));
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
  scene->finalize(progress);
  return scene;
}

}  // namespace torte
