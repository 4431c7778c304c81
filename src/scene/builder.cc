#include "scene/builder.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <map>
#include <unordered_set>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/memory_budget.h"
#include "core/text.h"

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
  // The object's entry in Scene::alpha_masks (one per masked material), or -1.
  std::map<const MaterialDesc*, int32_t> alpha_of;
  int32_t alpha_mask(const ShapeDesc& s) {
    const MaterialDesc* m = s.material.get();
    if (!m || !m->alpha_masked) return -1;
    if (!s.emission.is_black())
      throw Error(shape_name(s) + ": an emitting shape cannot have a cut-out (masked) material");
    if (auto it = alpha_of.find(m); it != alpha_of.end()) return it->second;
    const int32_t index = int32_t(scene.alpha_masks.size());
    scene.alpha_masks.push_back({textures.add(m->alpha), m->alpha_cutoff, m->alpha_stochastic});
    alpha_of.emplace(m, index);
    return index;
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
        if (emits && sh->emission_texture)
          throw Error("voxel cell shape " + std::to_string(c.id) + ": textured emission is not supported inside voxel cells");
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
                  const uint32_t* idx = mesh.triangle(t);
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

  static std::string shape_name(const ShapeDesc& s) {
    if (!s.origin.empty()) return s.origin;
    return s.kind == ShapeDesc::Kind::Mesh ? "a mesh" : s.kind == ShapeDesc::Kind::Quadric ? "a quadric" : "a voxel grid";
  }

  // Places the shape in its set's space (the world, a prototype's or a voxel cell's), refusing coordinates that
  // the transform takes beyond kMaxCoordinate (where bounding boxes and their areas overflow).
  static void place(const ShapeDesc& s, std::vector<TriangleMesh>& meshes, std::vector<Quadric>& quadrics) {
    throw_if_interrupted("building the scene");
    if (s.kind == ShapeDesc::Kind::Mesh) {
      if (!s.mesh) throw Error("internal: mesh shape without a mesh");
      // Shares the shape's positions, uvs and triples (the script may hold the mesh too): no copy of a scan.
      TriangleMesh mesh = make_placed(s.mesh, s.transform);
      if (const int64_t v = mesh.vertex_out_of_range(); v >= 0)
        throw Error(shape_name(s) + ": vertex " + std::to_string(v) + " lies at (" + format_coordinates(mesh.position(uint32_t(v))) +
                    ") once placed by its transform, beyond the range +-" + format_number(kMaxCoordinate) +
                    " that the scene supports");
      meshes.push_back(std::move(mesh));
    } else {
      Quadric q = s.quadric;
      q.to_world = s.transform;
      const Bounds3f b = world_bounds(q);
      if (!in_coordinate_range(b.lo) || !in_coordinate_range(b.hi))
        throw Error(shape_name(s) + ": its transform places it beyond the range +-" + format_number(kMaxCoordinate) +
                    " that the scene supports (bounds from (" + format_coordinates(b.lo) + ") to (" + format_coordinates(b.hi) + "))");
      quadrics.push_back(q);
    }
  }

  uint32_t prototype(const SceneBuilder& group) {
    if (auto it = prototype_of.find(&group); it != prototype_of.end()) return it->second;
    auto proto = std::make_unique<Prototype>();
    std::vector<SceneObject> objects;
    for (const ShapeDesc* s : ordered(group.shapes_)) {
      if (!s->emission.is_black())
        throw Error(shape_name(*s) + ": an emitting shape in a group placed by an instance; area lights cannot be "
                    "instanced, add the emitter to the scene itself");
      if (s->kind == ShapeDesc::Kind::Voxel)
        proto->grids.push_back(voxel_grid(*s, false));
      else
        place(*s, proto->meshes, proto->quadrics);
      objects.push_back({material(s->material), -1, alpha_mask(*s)});
    }
    const uint32_t index = uint32_t(scene.prototypes.size());
    scene.prototypes.push_back(std::move(proto));
    prototype_objects.push_back(std::move(objects));
    prototype_of.emplace(&group, index);
    return index;
  }

  // What the placements of a group amount to once the nesting is unrolled (saturating at 2^62).
  struct Placed {
    uint64_t instances = 0, lights = 0;
  };
  std::map<const SceneBuilder*, Placed> placed_;

  static uint64_t saturating_add(uint64_t a, uint64_t b) { return std::min(a + b, uint64_t(1) << 62); }

  // Counted once per group (memoized), so a wide DAG of groups costs its size, not its number of paths.
  Placed count(const SceneBuilder& group, int depth) {
    if (depth > kMaxGroupNesting)
      throw Error("groups nest more than " + std::to_string(kMaxGroupNesting) +
                  " levels deep (does a group contain itself?)");
    if (auto it = placed_.find(&group); it != placed_.end()) return it->second;
    Placed p;
    p.instances = group.shapes_.empty() ? 0 : 1;
    p.lights = group.lights_.size();
    for (const InstanceDesc& inst : group.instances_) {
      if (!inst.group) throw Error("internal: instance without a group");
      const Placed c = count(*inst.group, depth + 1);
      p.instances = saturating_add(p.instances, c.instances);
      p.lights = saturating_add(p.lights, c.lights);
    }
    placed_.emplace(&group, p);
    return p;
  }

  // Refuses nestings that unroll into more instances or lights than the limits, before any is made.
  void check_counts(const std::vector<InstanceDesc>& top) {
    Placed total;
    for (const InstanceDesc& inst : top) {
      if (!inst.group) throw Error("internal: instance without a group");
      const Placed c = count(*inst.group, 1);
      total.instances = saturating_add(total.instances, c.instances);
      total.lights = saturating_add(total.lights, c.lights);
    }
    if (total.instances > kMaxInstances)
      throw Error("the nesting of groups places " + std::to_string(total.instances) + " instances; the limit is " +
                  std::to_string(kMaxInstances));
    if (total.lights > kMaxInstancedLights)
      throw Error("the nesting of groups places " + std::to_string(total.lights) + " lights; the limit is " +
                  std::to_string(kMaxInstancedLights));
    reserve_memory(checked_bytes(total.instances, sizeof(Instance), "instances") +
                       checked_bytes(total.lights, sizeof(Light), "instanced lights"),
                   "the scene's instances");
    scene.instances.reserve(size_t(total.instances));
  }

  // One instance per path through the nesting, and a placed copy of every light of the groups on that path;
  // `to_world` places `group`'s contents.
  void instantiate(const SceneBuilder& group, const Transform& to_world, int depth) {
    if (depth > kMaxGroupNesting) throw Error("internal: groups nest deeper than counted");
    if ((scene.instances.size() & 0xfff) == 0) throw_if_interrupted("building the scene");
    const float det = to_world.determinant3();
    if (!(std::fabs(det) > 0) || !std::isfinite(det))
      throw Error("an instance's transform (composed through the nesting of groups) is singular or not finite");
    if (!group.shapes_.empty()) scene.instances.push_back({to_world, prototype(group)});
    for (const Light& light : group.lights_) scene.lights.push_back(placed_light(light, to_world));
    for (const InstanceDesc& inst : group.instances_) {
      if (!inst.group) throw Error("internal: instance without a group");
      instantiate(*inst.group, to_world * inst.transform, depth + 1);
    }
  }
};

uint64_t SceneBuilder::new_stamp() {
  static std::atomic<uint64_t> next{1};
  return next.fetch_add(1, std::memory_order_relaxed);
}

SceneBuilder::SceneBuilder(SceneBuilder&& other) noexcept
    : shapes_(std::move(other.shapes_)),
      instances_(std::move(other.instances_)),
      lights_(std::move(other.lights_)),
      stamp_(other.stamp_) {
  other.shapes_.clear();
  other.instances_.clear();
  other.lights_.clear();
  other.restamp();
}

SceneBuilder& SceneBuilder::operator=(SceneBuilder&& other) noexcept {
  if (this == &other) return *this;
  shapes_ = std::move(other.shapes_);
  instances_ = std::move(other.instances_);
  lights_ = std::move(other.lights_);
  stamp_ = other.stamp_;
  other.shapes_.clear();
  other.instances_.clear();
  other.lights_.clear();
  other.restamp();
  return *this;
}

std::vector<uint64_t> SceneBuilder::fingerprint() const {
  // Iterative: scripts may nest groups deeper than flatten() accepts, and contain cycles that it refuses.
  std::vector<uint64_t> stamps;
  std::unordered_set<const SceneBuilder*> seen;
  std::vector<const SceneBuilder*> pending{this};
  while (!pending.empty()) {
    const SceneBuilder* b = pending.back();
    pending.pop_back();
    if (!b || !seen.insert(b).second) continue;
    stamps.push_back(b->stamp_);
    // Pushed in reverse, so groups are visited in the order flatten() meets them.
    for (auto it = b->instances_.rbegin(); it != b->instances_.rend(); ++it) pending.push_back(it->group.get());
    for (auto it = b->shapes_.rbegin(); it != b->shapes_.rend(); ++it)
      if (it->kind == ShapeDesc::Kind::Voxel && it->voxels)
        for (auto c = it->voxels->cells.rbegin(); c != it->voxels->cells.rend(); ++c) pending.push_back(c->shapes.get());
  }
  return stamps;
}

bool SceneBuilder::reaches(const SceneBuilder* target) const {
  if (this == target) return true;
  if (!target || !target->placed_.value) return false;  // nothing points at target: no walk needed
  std::unordered_set<const SceneBuilder*> seen;
  std::vector<const SceneBuilder*> pending{this};
  while (!pending.empty()) {
    const SceneBuilder* b = pending.back();
    pending.pop_back();
    if (b == target) return true;
    if (!b || !seen.insert(b).second) continue;
    for (const InstanceDesc& inst : b->instances_) pending.push_back(inst.group.get());
    for (const ShapeDesc& shape : b->shapes_)
      if (shape.kind == ShapeDesc::Kind::Voxel && shape.voxels)
        for (const auto& cell : shape.voxels->cells) pending.push_back(cell.shapes.get());
  }
  return false;
}

SceneBuilder::~SceneBuilder() {
  // Groups this one alone keeps alive hand their instances to the work list before they die, so each dies with
  // no instances left and no destructor recurses.
  std::vector<std::shared_ptr<const SceneBuilder>> pending;
  for (InstanceDesc& inst : instances_) pending.push_back(std::move(inst.group));
  instances_.clear();
  while (!pending.empty()) {
    std::shared_ptr<const SceneBuilder> g = std::move(pending.back());
    pending.pop_back();
    if (g && g.use_count() == 1) {
      // The last owner: nothing else can see the group any more, so emptying it is safe.
      auto& inner = const_cast<SceneBuilder&>(*g).instances_;
      for (InstanceDesc& inst : inner) pending.push_back(std::move(inst.group));
      inner.clear();
    }
  }
}

std::shared_ptr<Scene> SceneBuilder::flatten(ProgressCounter* progress, const AccelOptions* options) const {
  auto scene = std::make_shared<Scene>();
  scene->accel_options = options ? *options : accel_options_;
  Flattening f(*scene);

  for (const ShapeDesc* s : Flattening::ordered(shapes_)) {
    throw_if_interrupted("building the scene");
    const uint32_t object = uint32_t(scene->objects.size());
    if (s->kind == ShapeDesc::Kind::Voxel) {
      scene->grids.push_back(f.voxel_grid(*s, true));
      scene->objects.push_back({f.material(s->material), -1, f.alpha_mask(*s)});
      continue;
    }
    Flattening::place(*s, scene->meshes, scene->quadrics);
    SceneObject obj;
    obj.material = f.material(s->material);
    obj.alpha_mask = f.alpha_mask(*s);
    if (!s->emission.is_black()) {
      Light light;
      light.kind = LightKind::Area;
      light.origin = Flattening::shape_name(*s);
      light.radiance = s->emission;
      if (s->emission_texture) light.emission_texture = f.textures.add(ColorInput{Rgb(1), s->emission_texture});
      light.object = object;
      light.two_sided = s->two_sided;
      obj.area_light = int32_t(scene->lights.size());
      scene->lights.push_back(light);
    }
    scene->objects.push_back(obj);
  }
  f.check_counts(instances_);
  for (const InstanceDesc& inst : instances_) f.instantiate(*inst.group, inst.transform, 1);
  for (const auto& objects : f.prototype_objects)
    scene->objects.insert(scene->objects.end(), objects.begin(), objects.end());

  for (const Light& l : lights_) scene->lights.push_back(l);
  scene->textures = f.textures.finish();
  scene->finalize(progress);
  return scene;
}

}  // namespace torte
