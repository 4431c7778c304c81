// torte.mesh.*: triangle meshes loaded from PLY/OBJ files and grown by subdivision, as userdata that
// torte.shape.mesh{mesh = ...} places without copying; also torte.clock().
//
//   local m = torte.mesh.load("bunny.ply")           -- path relative to the current directory
//   local big = m:subdivide{levels = 2, displacement = 0.05, seed = 0}   -- or torte.mesh.subdivide(m, {...})
//   print(big.triangles, big.vertices, big.has_normals, big.has_uvs)
//   local lo, hi = big:bounds()                       -- {x, y, z}, {x, y, z}
//   big:save("big.ply")                               -- binary little-endian PLY, read back by torte.mesh.load
//   scene:add(torte.shape.mesh{mesh = big, material = ...})   -- or file = "bunny.ply"
#include <chrono>
#include <cmath>

#include "core/memory_budget.h"
#include "file_access.h"
#include "runtime.h"
#include "geometry/mesh_io.h"
#include "geometry/mesh_normals.h"
#include "geometry/ply.h"
#include "geometry/subdivide.h"
#include "obj_import.h"
#include "types.h"

namespace torte::lua {

namespace {

std::shared_ptr<TriangleMesh> check_mesh(lua_State* L, int idx, const char* fn) {
  auto m = to_object<TriangleMesh>(L, idx);
  if (!m) throw Error(std::string(fn) + " expects a torte.mesh, got " + type_name(L, idx));
  return m;
}

int l_load(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING) throw Error("torte.mesh.load expects a file name, got " + type_name(L, 1));
  const std::string path = resolve_script_path(L, lua_tostring(L, 1));
  check_read(L, path, "torte.mesh.load");
  if (is_obj_path(path)) {  // the mesh, then its materials (lua/obj_import.h)
    ObjData data = load_obj_file(path, "torte.mesh.load");
    push_obj_materials(L, data, "torte.mesh.load");
    push_object(L, std::make_shared<TriangleMesh>(std::move(data.mesh)));
    lua_insert(L, -2);
    return 2;
  }
  TriangleMesh mesh;
  try {
    mesh = load_mesh(path);
  } catch (const Error& e) {
    throw Error(std::string("torte.mesh.load: ") + e.what());
  }
  push_object(L, std::make_shared<TriangleMesh>(std::move(mesh)));
  return 1;
}

// subdivide(mesh, {levels = 1, displacement = 0, seed = 0}); the options table may be omitted.
int l_subdivide(lua_State* L) {
  const char* fn = "torte.mesh.subdivide";
  auto mesh = check_mesh(L, 1, fn);
  if (lua_isnoneornil(L, 2)) {
    lua_settop(L, 1);
    lua_newtable(L);
  }
  KwArgs kw(L, 2, fn);
  const int levels = kw.integer("levels", 1);
  const double displacement = kw.number("displacement", 0);
  const double seed = kw.number("seed", 0);
  kw.finish();
  if (levels < 0 || levels > 12) kw.fail("levels", "must be between 0 and 12, got " + std::to_string(levels));
  if (seed < 0 || seed != std::floor(seed) || seed >= 0x1p64) kw.fail("seed", "must be a non-negative integer");
  TriangleMesh out;
  try {
    out = subdivide(*mesh, levels, float(displacement), uint64_t(seed));
  } catch (const Error& e) {
    std::string_view why = e.what();
    if (why.starts_with("subdivide: ")) why.remove_prefix(11);  // the function is named once
    throw Error(std::string(fn) + ": " + std::string(why));
  }
  push_object(L, std::make_shared<TriangleMesh>(std::move(out)));
  return 1;
}

// mesh:smooth_normals(): a copy with angle-weighted vertex normals (scans usually come without any).
int mesh_smooth_normals(lua_State* L) {
  auto mesh = check_mesh(L, 1, "torte.mesh.smooth_normals");
  const uint64_t copy_bytes = mesh->vertex_count() * sizeof(float) * 8 + mesh->indices.size() * sizeof(uint32_t);
  reserve_memory(copy_bytes, "torte.mesh.smooth_normals: a copy of " + std::to_string(mesh->triangle_count()) +
                                 " triangles");
  auto out = std::make_shared<TriangleMesh>(*mesh);
  compute_smooth_normals(*out);
  push_object(L, std::move(out));
  return 1;
}

int mesh_bounds(lua_State* L) {
  auto mesh = check_mesh(L, 1, "bounds");
  Bounds3f b;
  for (size_t i = 0; i < mesh->vertex_count(); ++i) b.extend(mesh->position(uint32_t(i)));
  if (b.empty()) throw Error("bounds: the mesh has no vertices");
  for (const Vec3f& p : {b.lo, b.hi}) {
    lua_createtable(L, 3, 0);
    for (int k = 0; k < 3; ++k) {
      lua_pushnumber(L, p[k]);
      lua_rawseti(L, -2, k + 1);
    }
  }
  return 2;
}

// mesh:fit{height = h | width = w | size = s, center = {x, y, z}, floor = false}: the transform that scales the
// mesh uniformly (height: its y extent; width: the larger of its x and z extents; size: its largest extent) and
// moves its bounds' centre to `center`, or, with floor = true, its bounds' bottom centre (the lowest y) there.
int mesh_fit(lua_State* L) {
  const char* fn = "torte.mesh.fit";
  auto mesh = check_mesh(L, 1, fn);
  if (lua_isnoneornil(L, 2)) {
    lua_settop(L, 1);
    lua_newtable(L);
  }
  KwArgs kw(L, 2, fn);
  const int given = int(kw.has("height")) + int(kw.has("width")) + int(kw.has("size"));
  if (given > 1) kw.fail("height", "cannot be combined with 'width' or 'size' (give one)");
  const char* key = kw.has("width") ? "width" : kw.has("size") ? "size" : "height";
  const double target = kw.number(key, 1);
  const Vec3f center = kw.vec3("center", Vec3f(0, 0, 0));
  const bool floor = kw.boolean("floor", false);
  kw.finish();
  if (!(target > 0) || !std::isfinite(target)) kw.fail(key, "must be positive and finite");
  Bounds3f b;
  for (size_t i = 0; i < mesh->vertex_count(); ++i) b.extend(mesh->position(uint32_t(i)));
  if (b.empty()) throw Error(std::string(fn) + ": the mesh has no vertices");
  const Vec3f ext = b.hi - b.lo;
  const float extent = key[0] == 'h' ? ext.y : key[0] == 'w' ? std::max(ext.x, ext.z)
                                                                : std::max({ext.x, ext.y, ext.z});
  if (!(extent > 0)) kw.fail(key, "cannot be fitted: the mesh is flat along it");
  const float s = float(target / double(extent));
  Vec3f anchor = (b.lo + b.hi) * 0.5f;
  if (floor) anchor.y = b.lo.y;
  push_transform(L, translate(center) * scale(Vec3f(s, s, s)) * translate(anchor * -1.0f));
  return 1;
}

// mesh:save(path): binary little-endian PLY (geometry/ply.h); only .ply is written.
int mesh_save(lua_State* L) {
  auto mesh = check_mesh(L, 1, "torte.mesh.save");
  if (lua_type(L, 2) != LUA_TSTRING) throw Error("torte.mesh.save expects a file name, got " + type_name(L, 2));
  const std::string path = lua_tostring(L, 2);
  if (path.size() < 4 || path.compare(path.size() - 4, 4, ".ply") != 0)
    throw Error("torte.mesh.save: '" + path + "' must end in .ply (the only format it writes)");
  check_write(L, path, "torte.mesh.save");
  try {
    write_ply(*mesh, path);
  } catch (const Error& e) {
    throw Error(std::string("torte.mesh.save: ") + e.what());
  }
  return 0;
}

int mesh_index(lua_State* L) {
  auto mesh = check_mesh(L, 1, "mesh field");
  const std::string key = luaL_checkstring(L, 2);
  if (key == "triangles") {
    lua_pushinteger(L, lua_Integer(mesh->triangle_count()));
  } else if (key == "vertices") {
    lua_pushinteger(L, lua_Integer(mesh->vertex_count()));
  } else if (key == "has_normals") {
    lua_pushboolean(L, mesh->has_normals());
  } else if (key == "has_uvs") {
    lua_pushboolean(L, mesh->has_uvs());
  } else if (push_method(L, 1, key)) {
  } else {
    throw Error("torte.mesh has no field '" + key +
                "' (fields: triangles, vertices, has_normals, has_uvs; methods: subdivide, smooth_normals, bounds, fit, save)");
  }
  return 1;
}

int mesh_tostring(lua_State* L) {
  auto mesh = check_mesh(L, 1, "tostring");
  lua_pushfstring(L, "torte.mesh (%I triangles, %I vertices)", lua_Integer(mesh->triangle_count()),
                  lua_Integer(mesh->vertex_count()));
  return 1;
}

// Wall-clock seconds from an arbitrary start (steady: differences time a step; os.clock() is CPU time, which
// counts every thread of a parallel step).
int l_clock(lua_State* L) {
  lua_pushnumber(L, std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count());
  return 1;
}

}  // namespace

std::shared_ptr<const TriangleMesh> mesh_argument(KwArgs& kw) {
  const bool has_mesh = kw.has("mesh"), has_file = kw.has("file");
  if (!has_mesh && !has_file) return nullptr;
  if (has_mesh && has_file) kw.fail("file", "cannot be given together with 'mesh'");
  std::shared_ptr<const TriangleMesh> mesh;
  if (has_mesh) {
    mesh = kw.object<TriangleMesh>("mesh");
  } else {
    const std::string path = resolve_script_path(kw.state(), kw.string("file"));
    check_read(kw.state(), path, kw.function().c_str());
    try {
      mesh = std::make_shared<const TriangleMesh>(load_mesh(path));
    } catch (const Error& e) {
      throw Error(kw.function() + ": " + e.what());
    }
  }
  if (mesh->triangle_count() == 0) kw.fail(has_mesh ? "mesh" : "file", "has no triangles");
  return mesh;
}

void open_meshes(lua_State* L, int torte_index) {
  // The metatable gets its fields once; push_object creates it on first use, so make a mesh now.
  push_object(L, std::make_shared<TriangleMesh>());
  lua_getmetatable(L, -1);
  lua_pushcfunction(L, guarded<mesh_index>);
  lua_setfield(L, -2, "__index");
  lua_pushcfunction(L, guarded<mesh_tostring>);
  lua_setfield(L, -2, "__tostring");
  const luaL_Reg methods[] = {{"subdivide", guarded<l_subdivide>}, {"smooth_normals", guarded<mesh_smooth_normals>},
                              {"bounds", guarded<mesh_bounds>},    {"fit", guarded<mesh_fit>},
                              {"save", guarded<mesh_save>},        {nullptr, nullptr}};
  set_methods(L, methods);
  lua_pop(L, 2);

  const luaL_Reg fns[] = {{"load", guarded<l_load>}, {"subdivide", guarded<l_subdivide>}, {nullptr, nullptr}};
  push_subtable(L, torte_index, "mesh");
  set_functions(L, fns);
  lua_pop(L, 1);
  lua_pushcfunction(L, l_clock);
  lua_setfield(L, torte_index, "clock");
}

}  // namespace torte::lua
