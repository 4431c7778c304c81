// torte.shape.* constructors and transforms (torte.translate, torte.scale, torte.rotate, torte.matrix; `*`
// composes, applying the right operand first).
#include <algorithm>
#include <cmath>

#include "file_access.h"
#include "geometry/mesh.h"
#include "obj_import.h"
#include "origin.h"
#include "runtime.h"
#include "texture_param.h"
#include "types.h"

namespace torte::lua {

namespace {
int transform_mul(lua_State* L);
int transform_inverse(lua_State* L);
int transform_apply(lua_State* L);
}  // namespace

void push_transform(lua_State* L, const Transform& t) {
  push_object(L, std::make_shared<Transform>(t));
  if (lua_getmetatable(L, -1)) {
    lua_getfield(L, -1, "__mul");
    const bool has = !lua_isnil(L, -1);
    lua_pop(L, 1);
    if (!has) {
      lua_pushcfunction(L, guarded<transform_mul>);
      lua_setfield(L, -2, "__mul");
      lua_newtable(L);
      lua_pushcfunction(L, guarded<transform_inverse>);
      lua_setfield(L, -2, "inverse");
      lua_pushcfunction(L, guarded<transform_apply>);
      lua_setfield(L, -2, "point");
      lua_setfield(L, -2, "__index");
    }
    lua_pop(L, 1);
  }
}

namespace {

bool is_finite_transform(const Transform& t) {
  for (const auto& row : t.matrix().m)
    for (float v : row)
      if (!std::isfinite(v)) return false;
  return true;
}

int transform_mul(lua_State* L) {
  auto a = to_object<Transform>(L, 1), b = to_object<Transform>(L, 2);
  if (!a || !b) throw Error("only two transforms can be multiplied");
  const Transform t = *a * *b;
  if (!is_finite_transform(t)) throw Error("the product of the two transforms is not finite (it overflows float)");
  push_transform(L, t);
  return 1;
}

int transform_inverse(lua_State* L) {
  auto a = to_object<Transform>(L, 1);
  if (!a) throw Error("inverse: expects a transform");
  push_transform(L, a->inverse());
  return 1;
}

int transform_apply(lua_State* L) {  // t:point{x,y,z} -> {x,y,z}
  auto a = to_object<Transform>(L, 1);
  if (!a) throw Error("point: expects a transform");
  const Vec3f p = a->apply_point(check_vec3(L, 2, "point"));
  lua_createtable(L, 3, 0);
  for (int i = 0; i < 3; ++i) {
    lua_pushnumber(L, p[i]);
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}

// Accepts (x, y, z), ({x, y, z}) or, if allow_scalar, (s) meaning (s, s, s).
Vec3f vec3_args(lua_State* L, const char* fn, bool allow_scalar) {
  if (lua_istable(L, 1)) return check_vec3(L, 1, std::string(fn) + " argument");
  if (allow_scalar && lua_gettop(L) == 1 && lua_type(L, 1) == LUA_TNUMBER) {
    const float s = float(lua_tonumber(L, 1));
    if (!std::isfinite(s)) throw Error(std::string(fn) + " expects finite numbers");
    return {s, s, s};
  }
  Vec3f v;
  for (int i = 0; i < 3; ++i) {
    if (lua_type(L, i + 1) != LUA_TNUMBER)
      throw Error(std::string(fn) + " expects three numbers or a table {x, y, z}");
    v[i] = float(lua_tonumber(L, i + 1));
    if (!std::isfinite(v[i])) throw Error(std::string(fn) + " expects finite numbers");
  }
  return v;
}

int l_translate(lua_State* L) { push_transform(L, translate(vec3_args(L, "torte.translate", false))); return 1; }
int l_scale(lua_State* L) { push_transform(L, scale(vec3_args(L, "torte.scale", true))); return 1; }
int l_identity(lua_State* L) { push_transform(L, Transform()); return 1; }

int l_rotate(lua_State* L) {
  if (lua_type(L, 1) != LUA_TNUMBER) throw Error("torte.rotate expects (degrees, {x, y, z})");
  const float deg = float(lua_tonumber(L, 1));
  if (!std::isfinite(deg)) throw Error("torte.rotate expects a finite angle");
  push_transform(L, rotate(deg, check_vec3(L, 2, "torte.rotate axis")));
  return 1;
}

int l_matrix(lua_State* L) {  // 16 numbers, row-major
  luaL_checktype(L, 1, LUA_TTABLE);
  if (lua_rawlen(L, 1) != 16) throw Error("torte.matrix expects 16 numbers (row-major 4x4)");
  Mat4 m;
  for (int i = 0; i < 16; ++i) {
    lua_rawgeti(L, 1, i + 1);
    if (lua_type(L, -1) != LUA_TNUMBER) throw Error("torte.matrix expects 16 numbers (row-major 4x4)");
    m.m[i / 4][i % 4] = float(lua_tonumber(L, -1));
    if (!std::isfinite(m.m[i / 4][i % 4])) throw Error("torte.matrix expects finite numbers");
    lua_pop(L, 1);
  }
  if (m.m[3][0] != 0 || m.m[3][1] != 0 || m.m[3][2] != 0 || m.m[3][3] != 1)
    throw Error("torte.matrix: only affine transforms are supported (last row must be 0 0 0 1)");
  push_transform(L, Transform(m));
  return 1;
}

// Keys every shape accepts: transform, material, emission, two_sided.
ShapeDesc common_shape(KwArgs& kw) {
  ShapeDesc s;
  s.origin = made_at(kw.state(), kw.function());
  s.transform = kw.transform("transform");
  s.material = kw.object<MaterialDesc>("material", true);
  // A colour, or a colour texture: the emitted radiance at each point (scale it with the texture operators).
  const ColorInput emission = color_input(kw, "emission", Rgb(0));
  s.emission = emission.texture ? Rgb(1) : emission.value;
  s.emission_texture = emission.texture;
  s.two_sided = kw.boolean("two_sided", false);
  const float det = s.transform.determinant3();
  if (!(std::fabs(det) >= 1e-20f) || !std::isfinite(det)) kw.fail("transform", "is singular or not finite");
  if (s.emission.max_component() > kMaxEmission) kw.fail("emission", "must be at most 1e20 per channel");
  return s;
}

int make_quadric(lua_State* L, const char* fn, QuadricKind kind) {
  KwArgs kw(L, 1, fn);
  ShapeDesc s = common_shape(kw);
  s.kind = ShapeDesc::Kind::Quadric;
  s.quadric.kind = kind;
  s.quadric.radius = float(kw.number("radius", 1));
  if (kind == QuadricKind::Disk) s.quadric.inner_radius = float(kw.number("inner_radius", 0));
  if (kind == QuadricKind::Cylinder) {
    s.quadric.z_min = float(kw.number("z_min", -1));
    s.quadric.z_max = float(kw.number("z_max", 1));
  }
  kw.finish();
  try {
    validate(s.quadric);
  } catch (const Error& e) {
    throw Error(std::string(fn) + ": " + e.what());
  }
  Quadric placed = s.quadric;
  placed.to_world = s.transform;
  const Bounds3f b = world_bounds(placed);
  if (!in_coordinate_range(b.lo) || !in_coordinate_range(b.hi))
    kw.fail("radius", "and the transform place the shape beyond +-1e18, the range the scene supports");
  push_object(L, std::make_shared<ShapeDesc>(std::move(s)));
  return 1;
}

int l_sphere(lua_State* L) { return make_quadric(L, "torte.shape.sphere", QuadricKind::Sphere); }
int l_disk(lua_State* L) { return make_quadric(L, "torte.shape.disk", QuadricKind::Disk); }
int l_cylinder(lua_State* L) { return make_quadric(L, "torte.shape.cylinder", QuadricKind::Cylinder); }

int push_mesh_shape(lua_State* L, ShapeDesc s, TriangleMesh mesh, const char* fn) {
  mesh.validate(fn);
  s.kind = ShapeDesc::Kind::Mesh;
  s.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
  push_object(L, std::make_shared<ShapeDesc>(std::move(s)));
  return 1;
}

// cube{} is [-1,1]^3 under its transform; cube{min=..., max=...} spans the given corners.
int l_cube(lua_State* L) {
  const char* fn = "torte.shape.cube";
  KwArgs kw(L, 1, fn);
  ShapeDesc s = common_shape(kw);
  TriangleMesh mesh = make_cube();
  if (kw.has("min") || kw.has("max")) {
    const Vec3f lo = kw.vec3("min"), hi = kw.vec3("max");
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) kw.fail("max", "must be greater than 'min' on every axis");
    mesh.transform(translate((lo + hi) * 0.5f) * scale((hi - lo) * 0.5f));
  }
  kw.finish();
  return push_mesh_shape(L, std::move(s), std::move(mesh), fn);
}

int l_polygon(lua_State* L) {
  const char* fn = "torte.shape.polygon";
  KwArgs kw(L, 1, fn);
  ShapeDesc s = common_shape(kw);
  const std::vector<double> pts = kw.numbers("points");
  kw.finish();
  if (pts.size() % 3 != 0 || pts.size() < 9) kw.fail("points", "must hold at least 3 points {x, y, z}");
  std::vector<Vec3f> vs;
  for (size_t i = 0; i < pts.size(); i += 3) vs.emplace_back(float(pts[i]), float(pts[i + 1]), float(pts[i + 2]));
  // A polygon must be planar: the fan triangles must share one plane.
  const Vec3f n = cross(vs[1] - vs[0], vs[2] - vs[0]);
  if (length_squared(n) == 0) kw.fail("points", "must not start with three collinear points");
  const Vec3f un = normalize(n);
  float extent = 0;
  for (const Vec3f& v : vs) extent = std::max(extent, length(v - vs[0]));
  for (const Vec3f& v : vs)
    if (std::fabs(dot(v - vs[0], un)) > 1e-4f * extent) kw.fail("points", "must lie in one plane");
  return push_mesh_shape(L, std::move(s), make_polygon(vs), fn);
}

// mesh{positions=..., indices=... (0-based), normals=?, uvs=?}, or mesh{mesh=<torte.mesh>} / mesh{file="path"}.
// An OBJ file with usemtl statements and no material= gives an array of shapes, one per MTL material.
int l_mesh(lua_State* L) {
  const char* fn = "torte.shape.mesh";
  KwArgs kw(L, 1, fn);
  ShapeDesc s = common_shape(kw);
  if (!s.material && !kw.has("mesh") && kw.has("file") && is_obj_path(kw.string("file"))) {
    // An OBJ file without a material from the script: its MTL materials, one shape per material (an array,
    // which scene:add takes like a shape); its Ke makes area lights unless the script gives an emission.
    const std::string path = resolve_script_path(L, kw.string("file"));
    kw.finish();
    check_read(L, path, fn);
    const ObjData data = load_obj_file(path, fn);
    if (data.mesh.triangle_count() == 0) kw.fail("file", "has no triangles");
    const bool has_materials = std::any_of(data.triangle_material.begin(), data.triangle_material.end(),
                                           [](int32_t m) { return m >= 0; });
    if (has_materials) {
      push_obj_shapes(L, data, s, s.emission.is_black(), fn);
      return 1;
    }
    return push_mesh_shape(L, std::move(s), data.mesh, fn);
  }
  if (auto shared = mesh_argument(kw)) {  // shared, not copied: meshes are never changed after creation
    kw.finish();
    s.kind = ShapeDesc::Kind::Mesh;
    s.mesh = std::move(shared);
    push_object(L, std::make_shared<ShapeDesc>(std::move(s)));
    return 1;
  }
  TriangleMesh mesh;
  const std::vector<double> pos = kw.numbers("positions");
  const std::vector<double> idx = kw.numbers("indices");
  if (pos.size() % 3 != 0) kw.fail("positions", "must hold 3 numbers per vertex");
  for (size_t i = 0; i < pos.size(); i += 3) mesh.add_vertex({float(pos[i]), float(pos[i + 1]), float(pos[i + 2])});
  for (double v : idx) {
    if (v < 0 || v != std::floor(v) || v > 4294967295.0) kw.fail("indices", "must be non-negative integers (0-based)");
    mesh.indices.push_back(uint32_t(v));
  }
  if (kw.has("normals")) {
    const std::vector<double> n = kw.numbers("normals");
    if (n.size() != pos.size()) kw.fail("normals", "must hold one normal per vertex");
    for (size_t i = 0; i < n.size(); i += 3) {
      Vec3f v{float(n[i]), float(n[i + 1]), float(n[i + 2])};
      if (!is_finite(v)) kw.fail("normals", "entry " + std::to_string(i / 3 + 1) + " is not finite");
      if (!(length_squared(v) > 0)) kw.fail("normals", "must be non-zero");
      v = normalize(v);
      mesh.nx.push_back(v.x); mesh.ny.push_back(v.y); mesh.nz.push_back(v.z);
    }
  } else {
    kw.push("normals");
    lua_pop(L, 1);
  }
  if (kw.has("uvs")) {
    const std::vector<double> uv = kw.numbers("uvs");
    if (uv.size() != 2 * mesh.vertex_count()) kw.fail("uvs", "must hold one {u, v} per vertex");
    for (size_t i = 0; i < uv.size(); i += 2) {
      mesh.u.push_back(float(uv[i]));
      mesh.v.push_back(float(uv[i + 1]));
    }
  } else {
    kw.push("uvs");
    lua_pop(L, 1);
  }
  kw.finish();
  if (mesh.triangle_count() == 0) kw.fail("indices", "must describe at least one triangle");
  return push_mesh_shape(L, std::move(s), std::move(mesh), fn);
}

}  // namespace

void open_geometry(lua_State* L, int torte_index) {
  const luaL_Reg transforms[] = {{"translate", guarded<l_translate>}, {"scale", guarded<l_scale>},
                                 {"rotate", guarded<l_rotate>},       {"matrix", guarded<l_matrix>},
                                 {"identity", guarded<l_identity>},   {nullptr, nullptr}};
  lua_pushvalue(L, torte_index);
  set_functions(L, transforms);
  lua_pop(L, 1);
  const luaL_Reg shapes[] = {{"sphere", guarded<l_sphere>}, {"disk", guarded<l_disk>},
                             {"cylinder", guarded<l_cylinder>}, {"cube", guarded<l_cube>},
                             {"polygon", guarded<l_polygon>}, {"mesh", guarded<l_mesh>},
                             {nullptr, nullptr}};
  push_subtable(L, torte_index, "shape");
  set_functions(L, shapes);
  lua_pop(L, 1);
}

}  // namespace torte::lua
