// torte.material.*, torte.light.* and torte.camera.* constructors.
#include <cmath>

#include "types.h"

namespace torte::lua {

namespace {

int l_matte(lua_State* L) {
  KwArgs kw(L, 1, "torte.material.matte");
  auto m = std::make_shared<MaterialDesc>();
  m->type = MaterialType::Lambert;
  m->lambert.albedo = kw.rgb("color", Rgb(0.5f));
  kw.finish();
  if (m->lambert.albedo.max_component() > 1) kw.fail("color", "must be at most 1 per channel (energy conservation)");
  push_object(L, std::move(m));
  return 1;
}

int l_point(lua_State* L) {
  KwArgs kw(L, 1, "torte.light.point");
  auto l = std::make_shared<Light>();
  l->kind = LightKind::Point;
  l->position = kw.vec3("position");
  l->radiance = kw.rgb("intensity", Rgb(1));
  kw.finish();
  push_object(L, std::move(l));
  return 1;
}

int l_infinite(lua_State* L) {
  KwArgs kw(L, 1, "torte.light.infinite");
  auto l = std::make_shared<Light>();
  l->kind = LightKind::Infinite;
  l->radiance = kw.rgb("radiance", Rgb(1));
  kw.finish();
  push_object(L, std::move(l));
  return 1;
}

FovAxis fov_axis(KwArgs& kw) {
  const std::string axis = kw.string("fov_axis", "vertical");
  if (axis == "vertical" || axis == "y") return FovAxis::Vertical;
  if (axis == "horizontal" || axis == "x") return FovAxis::Horizontal;
  if (axis == "diagonal") return FovAxis::Diagonal;
  kw.fail("fov_axis", "must be \"vertical\", \"horizontal\" or \"diagonal\", got \"" + axis + "\"");
}

// Placement: either eye/look_at/up or a camera-to-world transform.
Transform camera_placement(KwArgs& kw) {
  if (kw.has("transform")) {
    if (kw.has("eye") || kw.has("look_at")) kw.fail("transform", "cannot be combined with eye/look_at");
    return kw.transform("transform");
  }
  const Vec3f eye = kw.vec3("eye", Vec3f(0, 0, 0));
  const Vec3f target = kw.vec3("look_at", Vec3f(0, 0, 1));
  const Vec3f up = kw.vec3("up", Vec3f(0, 1, 0));
  try {
    return look_at(eye, target, up);
  } catch (const Error& e) {
    throw Error(kw.function() + ": " + e.what());
  }
}

int l_perspective(lua_State* L) {
  KwArgs kw(L, 1, "torte.camera.perspective");
  auto c = std::make_shared<CameraDesc>();
  c->kind = CameraKind::Perspective;
  c->camera_to_world = camera_placement(kw);
  c->fov_degrees = float(kw.number("fov", 45));
  c->fov_axis = fov_axis(kw);
  kw.finish();
  if (!(c->fov_degrees > 0 && c->fov_degrees < 180)) kw.fail("fov", "must be in (0, 180) degrees");
  push_object(L, std::move(c));
  return 1;
}

int l_orthographic(lua_State* L) {
  KwArgs kw(L, 1, "torte.camera.orthographic");
  auto c = std::make_shared<CameraDesc>();
  c->kind = CameraKind::Orthographic;
  c->camera_to_world = camera_placement(kw);
  c->extent = float(kw.number("extent", 2));
  c->fov_axis = fov_axis(kw);
  kw.finish();
  if (!(c->extent > 0)) kw.fail("extent", "must be positive");
  push_object(L, std::move(c));
  return 1;
}

}  // namespace

void open_materials(lua_State* L, int torte_index) {
  const luaL_Reg fns[] = {{"matte", guarded<l_matte>}, {"lambert", guarded<l_matte>}, {nullptr, nullptr}};
  push_subtable(L, torte_index, "material");
  set_functions(L, fns);
  lua_pop(L, 1);
}

void open_lights(lua_State* L, int torte_index) {
  const luaL_Reg fns[] = {{"point", guarded<l_point>}, {"infinite", guarded<l_infinite>}, {nullptr, nullptr}};
  push_subtable(L, torte_index, "light");
  set_functions(L, fns);
  lua_pop(L, 1);
}

void open_cameras(lua_State* L, int torte_index) {
  const luaL_Reg fns[] = {{"perspective", guarded<l_perspective>},
                          {"orthographic", guarded<l_orthographic>},
                          {nullptr, nullptr}};
  push_subtable(L, torte_index, "camera");
  set_functions(L, fns);
  lua_pop(L, 1);
}

}  // namespace torte::lua
