// torte.light.* and torte.camera.* constructors (materials: bind_material.cc).
#include <algorithm>
#include <cmath>

#include "file_access.h"
#include "runtime.h"
#include "film/image_io.h"
#include "geometry/mesh.h"
#include "light/environment.h"
#include "light/sky.h"
#include "origin.h"
#include "types.h"

namespace torte::lua {

namespace {

constexpr float kDegrees = kPi / 180;

// An emitted quantity: finite, non-negative and at most kMaxEmission per channel.
void check_non_negative(KwArgs& kw, const char* key, Rgb c) {
  if (!c.is_finite() || c.r < 0 || c.g < 0 || c.b < 0) kw.fail(key, "must be finite and non-negative");
  if (c.max_component() > kMaxEmission) kw.fail(key, "must be at most 1e20 per channel");
}

// A light made by a binding, remembering where the script made it.
std::shared_ptr<Light> new_light(KwArgs& kw, LightKind kind) {
  auto l = std::make_shared<Light>();
  l->kind = kind;
  l->origin = made_at(kw.state(), kw.function());
  return l;
}

Vec3f unit_direction(KwArgs& kw, const char* key, Vec3f v) {
  const float len = length(v);
  if (!(len > 0) || !std::isfinite(len)) kw.fail(key, "must be a non-zero vector");
  return v / len;
}

int l_point(lua_State* L) {
  KwArgs kw(L, 1, "torte.light.point");
  auto l = new_light(kw, LightKind::Point);
  l->position = kw.vec3("position");
  l->radiance = kw.rgb("intensity", Rgb(1));
  kw.finish();
  if (!in_coordinate_range(l->position)) kw.fail("position", "must lie within +-1e18");
  check_non_negative(kw, "intensity", l->radiance);
  push_object(L, std::move(l));
  return 1;
}

int l_infinite(lua_State* L) {
  KwArgs kw(L, 1, "torte.light.infinite");
  auto l = new_light(kw, LightKind::Infinite);
  l->radiance = kw.rgb("radiance", Rgb(1));
  kw.finish();
  check_non_negative(kw, "radiance", l->radiance);
  push_object(L, std::move(l));
  return 1;
}

int l_spot(lua_State* L) {
  KwArgs kw(L, 1, "torte.light.spot");
  auto l = new_light(kw, LightKind::Spot);
  l->position = kw.vec3("position");
  if (kw.has("look_at") && kw.has("direction")) kw.fail("look_at", "cannot be combined with 'direction'");
  if (kw.has("look_at")) {
    const Vec3f target = kw.vec3("look_at");
    if (!(length(target - l->position) > 0)) kw.fail("look_at", "must differ from 'position'");
    l->direction = normalize(target - l->position);
  } else {
    kw.vec3("look_at", Vec3f());  // absent: registers the key for the "accepted keys" list
    l->direction = unit_direction(kw, "direction", kw.vec3("direction", Vec3f(0, -1, 0)));
  }
  l->radiance = kw.rgb("intensity", Rgb(1));
  const double angle = kw.number("angle", 30);
  const double falloff = kw.number("falloff", std::max(0.0, angle - 5));
  kw.finish();
  check_non_negative(kw, "intensity", l->radiance);
  if (!in_coordinate_range(l->position)) kw.fail("position", "must lie within +-1e18");
  if (!(angle > 0 && angle <= 180)) kw.fail("angle", "must be in (0, 180] degrees (the cone's half angle)");
  if (!(falloff >= 0 && falloff <= angle)) kw.fail("falloff", "must be in [0, angle] degrees");
  l->cos_total = std::cos(float(angle) * kDegrees);
  l->cos_falloff_start = std::cos(float(falloff) * kDegrees);
  push_object(L, std::move(l));
  return 1;
}

int l_directional(lua_State* L) {
  KwArgs kw(L, 1, "torte.light.directional");
  auto l = new_light(kw, LightKind::Distant);
  l->direction = unit_direction(kw, "direction", kw.vec3("direction"));
  if (kw.has("irradiance") && kw.has("radiance")) kw.fail("radiance", "cannot be combined with 'irradiance'");
  const char* key = kw.has("radiance") ? "radiance" : "irradiance";
  l->radiance = kw.rgb(key, Rgb(1));
  kw.rgb(key[0] == 'r' ? "irradiance" : "radiance", Rgb());  // absent: registers the alternative key
  kw.finish();
  check_non_negative(kw, key, l->radiance);
  push_object(L, std::move(l));
  return 1;
}

int l_environment(lua_State* L) {
  KwArgs kw(L, 1, "torte.light.environment");
  const std::string file = resolve_script_path(L, kw.string("file"));
  check_read(L, file, "torte.light.environment");
  const Transform to_world = kw.transform("transform");
  const Rgb scale = kw.rgb("scale", Rgb(1));
  kw.finish();
  check_non_negative(kw, "scale", scale);
  if (!is_similarity(to_world)) kw.fail("transform", "must be a rotation");
  auto l = new_light(kw, LightKind::Environment);
  try {
    const Image image = read_image(file);  // its errors name the file
    try {
      l->environment = make_environment_map(image, to_world, scale);
    } catch (const Error& e) {
      throw Error("'" + file + "': " + e.what());
    }
  } catch (const Error& e) {
    throw Error(kw.function() + ": " + e.what());
  }
  push_object(L, std::move(l));
  return 1;
}

int l_sky(lua_State* L) {
  KwArgs kw(L, 1, "torte.light.sky");
  SkyParams p;
  const bool angles = kw.has("sun_elevation") || kw.has("sun_azimuth");
  if (angles && kw.has("sun_direction"))
    kw.fail("sun_direction", "cannot be combined with 'sun_elevation'/'sun_azimuth'");
  if (angles) {
    const double el = kw.number("sun_elevation", 45), az = kw.number("sun_azimuth", 0);
    if (!(el >= 0 && el <= 90)) kw.fail("sun_elevation", "must be in [0, 90] degrees (the sun above the horizon)");
    if (!std::isfinite(az)) kw.fail("sun_azimuth", "must be finite");
    const float e = float(el) * kDegrees, a = float(az) * kDegrees;
    p.sun_direction = {std::sin(a) * std::cos(e), std::sin(e), std::cos(a) * std::cos(e)};
    kw.vec3("sun_direction", Vec3f());  // absent: registers the key
  } else {
    kw.number("sun_elevation", 0);  // absent: register the keys
    kw.number("sun_azimuth", 0);
    p.sun_direction = unit_direction(kw, "sun_direction", kw.vec3("sun_direction", Vec3f(0.5f, 0.7f, 0.5f)));
    if (p.sun_direction.y < 0) kw.fail("sun_direction", "must point above the horizon (y >= 0)");
  }
  p.turbidity = float(kw.number("turbidity", 3));
  p.scale = float(kw.number("scale", 1.0 / 40));
  p.sun = kw.boolean("sun", true);
  p.sun_radius_degrees = float(kw.number("sun_radius", 0.2665));
  kw.finish();
  if (!(p.turbidity >= 1.7f && p.turbidity <= 10)) kw.fail("turbidity", "must be in [1.7, 10]");
  if (!(p.scale > 0) || !std::isfinite(p.scale)) kw.fail("scale", "must be positive");
  if (!(p.sun_radius_degrees > 0 && p.sun_radius_degrees < 45)) kw.fail("sun_radius", "must be in (0, 45) degrees");
  auto l = new_light(kw, LightKind::Sky);
  try {
    l->sky = make_sky(p);
  } catch (const Error& e) {
    throw Error(kw.function() + ": " + e.what());
  }
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

// Placement: either eye/look_at/up or a camera-to-world transform. *target_distance receives |look_at - eye|
// (the default focus distance), or 0 with a transform.
Transform camera_placement(KwArgs& kw, float* target_distance) {
  *target_distance = 0;
  if (kw.has("transform")) {
    if (kw.has("eye") || kw.has("look_at") || kw.has("up"))
      kw.fail("transform", "cannot be combined with eye/look_at/up");
    const Transform t = kw.transform("transform");
    const float det = t.determinant3();
    if (!(std::fabs(det) > 1e-30f) || !std::isfinite(det)) kw.fail("transform", "is singular (a camera needs all three axes)");
    if (!in_coordinate_range(t.apply_point(Vec3f(0, 0, 0))))
      kw.fail("transform", "places the camera beyond +-1e18");
    return t;
  }
  const Vec3f eye = kw.vec3("eye", Vec3f(0, 0, 0));
  const Vec3f target = kw.vec3("look_at", Vec3f(0, 0, 1));
  const Vec3f up = kw.vec3("up", Vec3f(0, 1, 0));
  if (!in_coordinate_range(eye)) kw.fail("eye", "must lie within +-1e18");
  if (!in_coordinate_range(target)) kw.fail("look_at", "must lie within +-1e18");
  const Vec3f view = target - eye;
  if (!(length_squared(view) > 0)) kw.fail("look_at", "must differ from 'eye' (there is no viewing direction)");
  // Scaled by the largest component first, so tiny and huge vectors normalize without underflow or overflow.
  auto unit = [](Vec3f v) {
    const float m = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    return m > 0 ? normalize(v / m) : Vec3f();
  };
  if (!(length_squared(unit(up)) > 0)) kw.fail("up", "must be a non-zero vector");
  if (!(length_squared(cross(unit(up), unit(view))) >= 1e-12f))
    kw.fail("up", "must not be parallel to the viewing direction (look_at - eye)");
  *target_distance = length(view);
  try {
    return look_at(eye, target, unit(up));
  } catch (const Error& e) {
    throw Error(kw.function() + ": " + e.what());
  }
}

// Thin lens: aperture (lens radius, world units) and focus_distance (default: the distance to look_at).
void lens(KwArgs& kw, CameraDesc* c, float target_distance) {
  c->aperture_radius = float(kw.number("aperture", 0));
  const bool has_focus = kw.has("focus_distance");
  c->focus_distance = float(kw.number("focus_distance", target_distance > 0 ? target_distance : 1));
  if (!(c->aperture_radius >= 0) || !std::isfinite(c->aperture_radius))
    kw.fail("aperture", "must be finite and non-negative (the lens radius)");
  if (!(c->focus_distance > 0) || !std::isfinite(c->focus_distance)) kw.fail("focus_distance", "must be positive");
  if (c->aperture_radius > 0 && !has_focus && !(target_distance > 0))
    kw.fail("focus_distance", "is required with 'aperture' when the camera is placed by 'transform'");
}

int l_perspective(lua_State* L) {
  KwArgs kw(L, 1, "torte.camera.perspective");
  auto c = std::make_shared<CameraDesc>();
  c->kind = CameraKind::Perspective;
  float target_distance;
  c->camera_to_world = camera_placement(kw, &target_distance);
  lens(kw, c.get(), target_distance);
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
  float target_distance;
  c->camera_to_world = camera_placement(kw, &target_distance);
  lens(kw, c.get(), target_distance);
  c->extent = float(kw.number("extent", 2));
  c->fov_axis = fov_axis(kw);
  kw.finish();
  if (!(c->extent > 0) || !std::isfinite(c->extent)) kw.fail("extent", "must be positive");
  push_object(L, std::move(c));
  return 1;
}

}  // namespace

void open_lights(lua_State* L, int torte_index) {
  const luaL_Reg fns[] = {{"point", guarded<l_point>},
                          {"spot", guarded<l_spot>},
                          {"directional", guarded<l_directional>},
                          {"distant", guarded<l_directional>},
                          {"infinite", guarded<l_infinite>},
                          {"environment", guarded<l_environment>},
                          {"sky", guarded<l_sky>},
                          {nullptr, nullptr}};
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
