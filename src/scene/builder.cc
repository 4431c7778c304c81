#include "scene/builder.h"

#include <map>

#include "core/error.h"

namespace torte {

std::shared_ptr<Scene> SceneBuilder::flatten() const {
  auto scene = std::make_shared<Scene>();
  std::map<const MaterialDesc*, MaterialRef> material_refs;
  auto material_ref = [&](const std::shared_ptr<const MaterialDesc>& m) {
    static const MaterialDesc kDefault{};
    const MaterialDesc* desc = m ? m.get() : &kDefault;
    auto [it, inserted] = material_refs.try_emplace(desc);
    if (inserted) {
      it->second.type = desc->type;
      switch (desc->type) {
        case MaterialType::Lambert:
          it->second.index = uint32_t(scene->materials.lambert.size());
          scene->materials.lambert.push_back(desc->lambert);
          break;
        case MaterialType::Count: throw Error("internal: invalid material type");
      }
    }
    return it->second;
  };

  // Meshes come first in the object numbering, then quadrics (see Scene).
  std::vector<const ShapeDesc*> ordered;
  for (const ShapeDesc& s : shapes_)
    if (s.kind == ShapeDesc::Kind::Mesh) ordered.push_back(&s);
  for (const ShapeDesc& s : shapes_)
    if (s.kind == ShapeDesc::Kind::Quadric) ordered.push_back(&s);

  for (const ShapeDesc* s : ordered) {
    const uint32_t object = uint32_t(scene->objects.size());
    if (s->kind == ShapeDesc::Kind::Mesh) {
      TriangleMesh mesh = *s->mesh;
      mesh.transform(s->transform);
      scene->meshes.push_back(std::move(mesh));
    } else {
      Quadric q = s->quadric;
      q.to_world = s->transform;
      scene->quadrics.push_back(q);
    }
    SceneObject obj;
    obj.material = material_ref(s->material);
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
  for (const Light& l : lights_) scene->lights.push_back(l);
  scene->camera = camera_;
  scene->has_camera = has_camera_;
  scene->finalize();
  return scene;
}

}  // namespace torte
