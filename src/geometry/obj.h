// Wavefront OBJ reader with MTL materials.
//
// Reads v (extra vertex-colour values ignored), vt, vn, f (v, v/vt, v//vn, v/vt/vn; negative indices count back
// from the latest element), o/g, usemtl, mtllib; l, p, s and the free-form curve/surface statements are ignored.
// Polygons are fan-triangulated from their first vertex. A position referenced with different uv or normal
// indices becomes distinct vertices. MTL: newmtl, Kd, Ke and map_Kd (a file name, relative to the MTL file).
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "core/rgb.h"
#include "geometry/mesh.h"

namespace torte {

struct ObjMaterial {
  std::string name;
  Rgb kd{0.8f, 0.8f, 0.8f};  // diffuse reflectance (the MTL default when Kd is absent is unspecified; this is grey)
  Rgb ke;                    // emitted radiance (Ke), black if absent
  std::string map_kd;        // diffuse texture file, resolved against the MTL file's directory; empty if none
};

struct ObjData {
  TriangleMesh mesh;  // has uvs / normals only when every face corner names one
  std::vector<ObjMaterial> materials;       // from the mtllib files in order, then unknown names in usemtl
  std::vector<int32_t> triangle_material;   // per triangle: index into materials, -1 before any usemtl
  std::vector<std::string> groups;          // names of o/g statements in order of first use; "" = no group
  std::vector<uint32_t> triangle_group;     // per triangle: index into groups
  std::vector<std::string> warnings;        // e.g. a missing mtllib file or an unknown material name
};

// Throws torte::Error("<path>: line N: ...") for bad statements, numbers or out-of-range indices.
ObjData read_obj(const std::string& path);
// The same for text in memory; mtllib files are looked up in `base_dir` ("" = current directory).
ObjData parse_obj(std::string_view text, const std::string& name, const std::string& base_dir);

}  // namespace torte
