// Triangle mesh in structure-of-arrays form: positions, optional vertex normals and uvs, index triples.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/bounds.h"
#include "core/transform.h"
#include "core/vec.h"

namespace torte {

/// Every coordinate of a scene, in object and in world space, lies within +-kMaxCoordinate: bounding boxes,
/// their areas (the BVH's cost) and ray distances then stay finite in float.
constexpr float kMaxCoordinate = 1e18f;
inline bool in_coordinate_range(Vec3f p) {
  return std::fabs(p.x) <= kMaxCoordinate && std::fabs(p.y) <= kMaxCoordinate && std::fabs(p.z) <= kMaxCoordinate;
}
/// "1.8e+19, 0, 0" for messages.
std::string format_coordinates(Vec3f p);

struct TriangleMesh {
  std::vector<float> x, y, z;     // positions
  std::vector<float> nx, ny, nz;  // vertex normals, empty when the mesh has none
  std::vector<float> u, v;        // texture coordinates, empty when the mesh has none
  std::vector<uint32_t> indices;  // three per triangle, counter-clockwise seen from the front face
  // A placed mesh (make_placed) reads its positions, uvs and index triples from `source` instead of copying
  // them: positions through `to_world`, triples from its own `indices` only when those are not empty (a
  // mirroring placement, which swaps the winding). A scan of 28 M triangles would otherwise be held twice, once
  // by the script and once by the scene. `source` is never itself placed.
  std::shared_ptr<const TriangleMesh> source;
  Transform to_world;

  bool placed() const { return source != nullptr; }
  size_t vertex_count() const { return placed() ? source->x.size() : x.size(); }
  size_t triangle_count() const { return triple_array().size() / 3; }
  bool has_normals() const { return !nx.empty(); }
  bool has_uvs() const { return placed() ? source->has_uvs() : !u.empty(); }
  Vec3f position(uint32_t i) const {
    // Not recursive (a source is never placed), so the builder's per-vertex loops inline it.
    const TriangleMesh& m = placed() ? *source : *this;
    const Vec3f p{m.x[i], m.y[i], m.z[i]};
    return placed() ? to_world.apply_point(p) : p;
  }
  Vec3f normal(uint32_t i) const { return {nx[i], ny[i], nz[i]}; }
  Vec2f uv(uint32_t i) const { return placed() ? source->uv(i) : Vec2f(u[i], v[i]); }
  /// The three vertex indices of triangle t.
  const uint32_t* triangle(size_t t) const { return triple_array().data() + 3 * t; }
  /// The index triples in use: the own ones, or the source's for a placed mesh that has none of its own.
  const std::vector<uint32_t>& triple_array() const {
    return placed() && indices.empty() ? source->indices : indices;
  }
  void add_vertex(Vec3f p) { x.push_back(p.x); y.push_back(p.y); z.push_back(p.z); }
  void add_triangle(uint32_t a, uint32_t b, uint32_t c) { indices.insert(indices.end(), {a, b, c}); }

  // Throws torte::Error (prefixed by `what`, e.g. the file or the function) naming the vertex or triangle, for
  // mismatched array sizes, out-of-range indices, positions that are not finite or beyond kMaxCoordinate, and
  // normals or uvs that are not finite.
  void validate(const std::string& what) const;
  // The first vertex whose position is not finite or beyond kMaxCoordinate, or -1.
  int64_t vertex_out_of_range() const;
  // Bytes this mesh holds itself (a placed mesh's source is not counted).
  size_t own_bytes() const;
  // Maps positions and normals to world space in place (normals by the inverse transpose, not renormalized per
  // vertex, so interpolation commutes with the transform; handedness flips keep the winding-defined front face,
  // so the geometric normal stays outward).
  void transform(const Transform& t);
  Bounds3f triangle_bounds(size_t tri) const;
  float triangle_area(size_t tri) const;
};

/// `source` (validated, not placed) placed by `t`: shares its positions, uvs and triples, holds the normals
/// mapped as TriangleMesh::transform maps them (and swapped triples when t mirrors).
TriangleMesh make_placed(std::shared_ptr<const TriangleMesh> source, const Transform& t);

// Meshes numbered one after another, mesh m's triangles from mesh_first[m] on (ascending, mesh_first[0] = 0):
// the mesh holding triangle g, the last one starting at or before g (an empty mesh starts where the next one does).
inline uint32_t mesh_holding(std::span<const uint32_t> mesh_first, uint32_t g) {
  // Hits reach meshes in random order, so a search's branches mispredict: a few meshes are counted instead.
  if (mesh_first.size() <= 16) {
    uint32_t m = 0;
    for (size_t j = 1; j < mesh_first.size(); ++j) m += uint32_t(mesh_first[j] <= g);
    return m;
  }
  return uint32_t(std::upper_bound(mesh_first.begin(), mesh_first.end(), g) - mesh_first.begin() - 1);
}

// Unit cube [-1,1]^3 as 12 outward-facing triangles with per-face uvs.
TriangleMesh make_cube();
// A planar polygon (convex or simple, given in order) triangulated as a fan from its first vertex. Throws
// torte::Error for fewer than 3 vertices.
TriangleMesh make_polygon(const std::vector<Vec3f>& vertices);

}  // namespace torte
