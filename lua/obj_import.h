// OBJ files with their MTL materials as torte objects: the materials mapped onto torte.material.* and the mesh
// split into one shape per material (docs/formats.md says what is approximated).
#pragma once
#include <string>

#include "geometry/obj.h"
#include "types.h"

namespace torte::lua {

/// Reads an OBJ file (read_obj) and prints its warnings (missing mtllib files, unknown material names and MTL
/// statements, unreadable texture files) to stderr, one line each. Errors: `function`: <read_obj's error>.
ObjData load_obj_file(const std::string& path, const std::string& function);

/// The torte material closest to an MTL material: matte (Kd, or map_Kd as an image texture), plastic when Ks is
/// not black (Ni as the coat's eta, Ns as its roughness), mixed with thin glass by 1 - d when d < 1, inside a bump
/// of map_Bump. A texture file that cannot be opened is a warning on stderr and the map is dropped.
std::shared_ptr<MaterialDesc> material_from_obj(lua_State* L, const ObjMaterial& m, const std::string& function);

/// Whether `path` ends in .obj (any case).
bool is_obj_path(const std::string& path);

/// Pushes an array of shapes, one per material of `data` (split_by_material), each a copy of `base` with the
/// mapped material and, when `use_emission`, the material's Ke as its emission (an area light).
void push_obj_shapes(lua_State* L, const ObjData& data, const ShapeDesc& base, bool use_emission,
                     const std::string& function);

/// Pushes the materials of `data` as an array of {name, material, emission, mesh} (mesh: that material's
/// triangles), each also under its name.
void push_obj_materials(lua_State* L, const ObjData& data, const std::string& function);

}  // namespace torte::lua
