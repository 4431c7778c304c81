// torte.voxel.grid{}: sparse voxel grids filled from Lua (chunk by chunk for speed), their id definitions, and
// their placement as shapes (g:shape{...} or torte.shape.voxels{grid = g, ...}). See src/voxel/.
//
//   local g = torte.voxel.grid{}
//   g:set(x, y, z, id)                      -- one voxel; ids are integers in [-32768, 32767], 0 = empty
//   g:set_chunk(cx, cy, cz, ids)            -- 4096 ids of chunk (cx, cy, cz), index (y*16 + z)*16 + x (0-based):
//                                           -- a table of 4096 integers or a string of 8192 bytes (int16, LE)
//   g:get(x, y, z), g:count(), g:chunks(), g:bounds() -> {lo}, {hi}
//   g:define{id = 1, material = m}          -- solid cube, one material
//   g:define{id = 2, material = m, faces = {top = m1, bottom = m2, side = m3}}  -- or "+x", "-x", "+y", ... "-z"
//   g:define{id = 4, material = m, emission = {8, 6, 3}}  -- an emitting cube: its exposed faces are area lights
//   g:define{id = -3, shape = group}        -- cell shape: a torte.group() of shapes modelling the unit cell [0,1]^3
//                                           -- (meshes in it may have emission = {...}: they emit on both sides)
//   g:build() -> {voxels, cells, nodes, bytes, bytes_per_voxel, seconds}  (cells: voxels of the padded box)   (done by g:shape when the grid changed)
//   g:save(path)                            -- raw chunk dump, for TORTE_BENCH_VOXEL_WORLD (bench/bench_voxel.cc)
//   scene:add(g:shape{transform = T, material = default})  -- or torte.shape.voxels{grid = g, ...}
#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>

#include "file_access.h"
#include "origin.h"
#include "types.h"
#include "voxel/voxel_shape.h"

namespace torte::lua {

struct VoxelGridObject {
  VoxelGrid grid;
  std::map<int16_t, VoxelCubeDef> cubes;
  std::map<int16_t, VoxelCellDef> cells;
  std::shared_ptr<const VoxelTree> tree;
  uint64_t tree_revision = 0;
};

template <> struct LuaName<VoxelGridObject> { static constexpr const char* value = "torte.voxel.grid"; };

namespace {

VoxelGridObject& self(lua_State* L, const char* method) {
  auto g = to_object<VoxelGridObject>(L, 1);
  if (!g) throw Error(std::string("grid:") + method + " must be called with ':' on a torte.voxel.grid");
  return *g;
}

int check_int(lua_State* L, int idx, const char* what) {
  int ok = 0;
  const lua_Integer v = lua_tointegerx(L, idx, &ok);
  if (!ok) throw Error(std::string(what) + " must be an integer, got " + type_name(L, idx));
  if (v < -(lua_Integer(1) << 30) || v >= (lua_Integer(1) << 30)) throw Error(std::string(what) + " is out of range");
  return int(v);
}

int16_t check_id(lua_State* L, int idx, const char* what) {
  const int v = check_int(L, idx, what);
  if (v < -32768 || v > 32767) throw Error(std::string(what) + " must be in [-32768, 32767], got " + std::to_string(v));
  return int16_t(v);
}

int grid_set(lua_State* L) {
  VoxelGridObject& g = self(L, "set");
  g.grid.set(check_int(L, 2, "grid:set x"), check_int(L, 3, "grid:set y"), check_int(L, 4, "grid:set z"),
             check_id(L, 5, "grid:set id"));
  return 0;
}

int grid_get(lua_State* L) {
  VoxelGridObject& g = self(L, "get");
  lua_pushinteger(L, g.grid.get(check_int(L, 2, "grid:get x"), check_int(L, 3, "grid:get y"), check_int(L, 4, "grid:get z")));
  return 1;
}

int grid_set_chunk(lua_State* L) {
  VoxelGridObject& g = self(L, "set_chunk");
  const int cx = check_int(L, 2, "grid:set_chunk cx"), cy = check_int(L, 3, "grid:set_chunk cy"),
            cz = check_int(L, 4, "grid:set_chunk cz");
  int16_t ids[kVoxelChunkVoxels];
  if (lua_type(L, 5) == LUA_TSTRING) {
    size_t len = 0;
    const auto* bytes = reinterpret_cast<const unsigned char*>(lua_tolstring(L, 5, &len));
    if (len != 2 * kVoxelChunkVoxels)
      throw Error("grid:set_chunk: the ids string must hold 8192 bytes (4096 int16, little-endian), got " +
                  std::to_string(len));
    for (int i = 0; i < kVoxelChunkVoxels; ++i) ids[i] = int16_t(uint16_t(bytes[2 * i] | bytes[2 * i + 1] << 8));
  } else if (lua_istable(L, 5)) {
    if (lua_rawlen(L, 5) != kVoxelChunkVoxels)
      throw Error("grid:set_chunk: the ids table must hold 4096 integers, got " + std::to_string(lua_rawlen(L, 5)));
    for (int i = 0; i < kVoxelChunkVoxels; ++i) {
      lua_rawgeti(L, 5, i + 1);
      int ok = 0;
      const lua_Integer v = lua_tointegerx(L, -1, &ok);
      if (!ok || v < -32768 || v > 32767)
        throw Error("grid:set_chunk: ids[" + std::to_string(i + 1) + "] must be an integer in [-32768, 32767]");
      ids[i] = int16_t(v);
      lua_pop(L, 1);
    }
  } else {
    throw Error("grid:set_chunk expects (cx, cy, cz, ids) with ids a table of 4096 integers or a string of 8192 "
                "bytes, got " + type_name(L, 5));
  }
  g.grid.set_chunk(cx, cy, cz, ids);
  return 0;
}

int grid_save(lua_State* L) {  // g:save(path): raw chunk dump (bench/bench_voxel.cc reads it)
  VoxelGridObject& g = self(L, "save");
  check_write(L, luaL_checkstring(L, 2), "grid:save");
  g.grid.save(luaL_checkstring(L, 2));
  return 0;
}

int grid_count(lua_State* L) {
  lua_pushinteger(L, lua_Integer(self(L, "count").grid.voxel_count()));
  return 1;
}

int grid_chunks(lua_State* L) {
  lua_pushinteger(L, lua_Integer(self(L, "chunks").grid.chunk_count()));
  return 1;
}

void push_ints(lua_State* L, const int* v) {
  lua_createtable(L, 3, 0);
  for (int i = 0; i < 3; ++i) {
    lua_pushinteger(L, v[i]);
    lua_rawseti(L, -2, i + 1);
  }
}

int grid_bounds(lua_State* L) {  // chunk-aligned box [lo, hi) of the chunks held
  int lo[3], hi[3];
  self(L, "bounds").grid.chunk_bounds(lo, hi);
  push_ints(L, lo);
  push_ints(L, hi);
  return 2;
}

// face keys of define{faces = {...}}: which faces each sets
struct FaceKey {
  const char* name;
  int faces[4];
};
constexpr FaceKey kFaceKeys[] = {{"side", {0, 1, 4, 5}}, {"top", {2, -1, -1, -1}}, {"bottom", {3, -1, -1, -1}},
                                 {"+x", {0, -1, -1, -1}}, {"-x", {1, -1, -1, -1}}, {"+y", {2, -1, -1, -1}},
                                 {"-y", {3, -1, -1, -1}}, {"+z", {4, -1, -1, -1}}, {"-z", {5, -1, -1, -1}}};

int grid_define(lua_State* L) {
  VoxelGridObject& g = self(L, "define");
  KwArgs kw(L, 2, "grid:define");
  kw.push("id");
  const int16_t id = check_id(L, -1, "grid:define: 'id'");
  lua_pop(L, 1);
  if (id == 0) kw.fail("id", "0 is the empty voxel and cannot be defined");
  if (id > 0) {
    VoxelCubeDef def;
    def.id = id;
    def.emission = kw.rgb("emission", Rgb(0));
    if (!(def.emission.r >= 0 && def.emission.g >= 0 && def.emission.b >= 0))
      kw.fail("emission", "must be a non-negative radiance {r, g, b}");
    if (def.emission.max_component() > kMaxEmission) kw.fail("emission", "must be at most 1e20 per channel");
    auto all = kw.object<MaterialDesc>("material", true);
    for (auto& f : def.faces) f = all;
    kw.push("faces");
    if (!lua_isnil(L, -1)) {
      if (!lua_istable(L, -1)) kw.fail("faces", "must be a table {top = m, bottom = m, side = m, ['+x'] = m, ...}");
      KwArgs faces(L, lua_gettop(L), "grid:define faces");
      for (const FaceKey& k : kFaceKeys)
        if (auto m = faces.object<MaterialDesc>(k.name, true))
          for (int f : k.faces)
            if (f >= 0) def.faces[size_t(f)] = m;
      faces.finish();
    }
    lua_pop(L, 1);
    kw.finish();
    g.cubes[id] = std::move(def);
  } else {
    VoxelCellDef def;
    def.id = id;
    kw.push("emission");
    if (!lua_isnil(L, -1))
      kw.fail("emission", "cell shapes emit through their own shapes: give the group's meshes an emission");
    lua_pop(L, 1);
    def.shapes = kw.object<SceneBuilder>("shape");
    kw.finish();
    g.cells[id] = std::move(def);
  }
  return 0;
}

std::shared_ptr<const VoxelTree> built(lua_State* L, VoxelGridObject& g) {
  if (g.tree && g.tree_revision == g.grid.revision()) return g.tree;
  g.tree = std::make_shared<const VoxelTree>(VoxelTree::build(g.grid));
  g.tree_revision = g.grid.revision();
  const VoxelBuildStats& s = g.tree->stats();
  if (!run_context(L).quiet)
    std::fprintf(stderr,
                 "voxel grid: %llu voxels in %zu chunks, box %dx%dx%d; kd-tree %llu nodes, %.2f MB, %.3f bytes/voxel; "
                 "built in %.1f ms\n",
                 static_cast<unsigned long long>(s.voxels), g.grid.chunk_count(), 1 << g.tree->log2_size()[0],
                 1 << g.tree->log2_size()[1], 1 << g.tree->log2_size()[2], static_cast<unsigned long long>(s.nodes),
                 double(s.bytes) / (1 << 20), s.bytes_per_voxel(), s.seconds * 1e3);
  return g.tree;
}

int grid_build(lua_State* L) {
  VoxelGridObject& g = self(L, "build");
  const VoxelBuildStats& s = built(L, g)->stats();
  lua_createtable(L, 0, 5);
  lua_pushinteger(L, lua_Integer(s.voxels));
  lua_setfield(L, -2, "voxels");
  lua_pushinteger(L, lua_Integer(s.nodes));
  lua_setfield(L, -2, "nodes");
  lua_pushinteger(L, lua_Integer(s.bytes));
  lua_setfield(L, -2, "bytes");
  lua_pushnumber(L, s.bytes_per_voxel());
  lua_setfield(L, -2, "bytes_per_voxel");
  lua_pushinteger(L, lua_Integer(s.cells));
  lua_setfield(L, -2, "cells");
  lua_pushnumber(L, s.seconds);
  lua_setfield(L, -2, "seconds");
  return 1;
}

// The shape of a grid: transform (cell space -> parent), material (ids without a definition).
int push_voxel_shape(lua_State* L, VoxelGridObject& g, KwArgs& kw) {
  auto s = std::make_shared<ShapeDesc>();
  s->kind = ShapeDesc::Kind::Voxel;
  s->transform = kw.transform("transform");
  if (std::fabs(s->transform.determinant3()) < 1e-20f) kw.fail("transform", "is singular");
  s->material = kw.object<MaterialDesc>("material", true);
  kw.finish();
  auto shape = std::make_shared<VoxelShape>();
  shape->tree = built(L, g);
  for (const auto& [id, def] : g.cubes) shape->cubes.push_back(def);
  for (const auto& [id, def] : g.cells) shape->cells.push_back(def);
  s->voxels = std::move(shape);
  push_object(L, std::move(s));
  return 1;
}

int grid_shape(lua_State* L) {
  VoxelGridObject& g = self(L, "shape");
  if (lua_isnoneornil(L, 2)) {
    lua_settop(L, 1);
    lua_newtable(L);
  }
  KwArgs kw(L, 2, "grid:shape");
  return push_voxel_shape(L, g, kw);
}

int l_shape_voxels(lua_State* L) {
  KwArgs kw(L, 1, "torte.shape.voxels");
  auto g = kw.object<VoxelGridObject>("grid");
  return push_voxel_shape(L, *g, kw);
}

int l_grid(lua_State* L) {
  if (!lua_isnoneornil(L, 1)) {  // an empty table is accepted; the grid takes no keys
    if (lua_istable(L, 1)) {
      lua_pushnil(L);
      if (lua_next(L, 1) != 0) {
        const std::string key = lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2) : luaL_typename(L, -2);
        throw Error("torte.voxel.grid takes no keys (got '" + key + "'); fill the grid with grid:set or grid:set_chunk");
      }
    }
    KwArgs kw(L, 1, "torte.voxel.grid");
    kw.finish();
  }
  push_object(L, std::make_shared<VoxelGridObject>());
  return 1;
}

}  // namespace

void open_voxels(lua_State* L, int torte_index) {
  push_object(L, std::make_shared<VoxelGridObject>());
  lua_getmetatable(L, -1);
  static const luaL_Reg methods[] = {{"set", guarded<grid_set>},         {"get", guarded<grid_get>},
                                     {"set_chunk", guarded<grid_set_chunk>}, {"count", guarded<grid_count>},
                                     {"chunks", guarded<grid_chunks>},   {"bounds", guarded<grid_bounds>},
                                     {"define", guarded<grid_define>},   {"build", guarded<grid_build>},
                                     {"shape", guarded<grid_shape>},     {"save", guarded<grid_save>},
                                     {nullptr, nullptr}};
  lua_newtable(L);
  set_functions(L, methods);
  lua_setfield(L, -2, "__index");
  lua_pop(L, 2);
  const luaL_Reg fns[] = {{"grid", guarded<l_grid>}, {nullptr, nullptr}};
  push_subtable(L, torte_index, "voxel");
  set_functions(L, fns);
  lua_pop(L, 1);
  const luaL_Reg shapes[] = {{"voxels", guarded<l_shape_voxels>}, {nullptr, nullptr}};
  push_subtable(L, torte_index, "shape");
  set_functions(L, shapes);
  lua_pop(L, 1);
}

}  // namespace torte::lua
