// Wavefront OBJ reader with MTL materials.
//
// Reads v (extra vertex-colour values ignored), vt, vn, f (v, v/vt, v//vn, v/vt/vn; negative indices count back
// from the latest element), o/g, usemtl, mtllib; l, p, s and the free-form curve/surface statements are ignored.
// Polygons are fan-triangulated from their first vertex. A position referenced with different uv or normal
// indices becomes distinct vertices. MTL: newmtl, Kd, Ks, Ns, Ni, d, Tr, Ke (Ka above 1 as Ke), map_Kd and map_Bump/bump (file names
// relative to the MTL file); other MTL statements (Ka, illum, other maps, ...) are ignored.
//
// Why not Debian's libtinyobjloader-dev (2.0.0~rc10): it reads damaged files without an error, which the renderer
// must not (a corrupt mesh is an error naming file and line, never a silently wrong image). Tried 2026-11-22 with
// ObjReader::ParseFromString: "v 1 abc 0" loads as (1, 0, 0), "v 0 1" as (0, 1, 0), "f 1 2 -5" on three vertices
// loads, and "f 1 2 7" only warns. This reader rejects all four (tests/test_mesh_io.cc).
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
  Rgb ks;                    // specular reflectance (Ks), black if absent
  float ns = 0;              // Phong specular exponent (Ns), 0 if absent
  float ni = 1.5f;           // index of refraction (Ni)
  float d = 1;               // opacity (d, or 1 - Tr)
  Rgb ke;                    // emitted radiance (Ke), black if absent; Ka when that exceeds 1 and Ke is absent
  Rgb ka;                    // ambient (Ka): read only for the Ke fallback
  std::string map_kd;        // diffuse texture file, resolved against the MTL file's directory; empty if none
  std::string map_bump;      // bump (height) map file (map_Bump or bump), resolved the same way
  float bump_scale = 1;      // its -bm option
  bool defined = false;      // false: named by usemtl but defined in no mtllib file
};

struct ObjData {
  TriangleMesh mesh;  // has uvs / normals only when every face corner names one
  std::vector<ObjMaterial> materials;       // from the mtllib files in order, then unknown names in usemtl
  std::vector<int32_t> triangle_material;   // per triangle: index into materials, -1 before any usemtl
  std::vector<std::string> groups;          // names of o/g statements in order of first use; "" = no group
  std::vector<uint32_t> triangle_group;     // per triangle: index into groups
  std::vector<std::string> warnings;        // e.g. a missing mtllib file or an unknown material name
};

/// The triangles of one material (ObjData::materials index, -1 = before any usemtl) as a mesh of their own,
/// keeping only the vertices they use; in order of first use.
struct ObjPart {
  int32_t material = -1;
  TriangleMesh mesh;
};
std::vector<ObjPart> split_by_material(const ObjData& data);

// Throws torte::Error("<path>: line N: ...") for bad statements, numbers or out-of-range indices.
ObjData read_obj(const std::string& path);
// The same for text in memory; mtllib files are looked up in `base_dir` ("" = current directory).
ObjData parse_obj(std::string_view text, const std::string& name, const std::string& base_dir);

}  // namespace torte
