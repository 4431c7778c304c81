#include "geometry/mesh.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/text.h"

namespace torte {

void TriangleMesh::validate(const std::string& what) const {
  const size_t n = x.size();
  if (y.size() != n || z.size() != n) throw Error(what + ": position arrays differ in length");
  if (has_normals() && (nx.size() != n || ny.size() != n || nz.size() != n))
    throw Error(what + ": there must be one normal per vertex");
  if (has_uvs() && (u.size() != n || v.size() != n)) throw Error(what + ": there must be one uv per vertex");
  if (indices.size() % 3 != 0) throw Error(what + ": the index count is not a multiple of 3");
  for (size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= n)
      throw Error(what + ": index " + std::to_string(indices[i]) + " of triangle " + std::to_string(i / 3) +
                  " is out of range (" + std::to_string(n) + " vertices)");
  if (const int64_t i = vertex_out_of_range(); i >= 0) {
    const Vec3f p = position(uint32_t(i));
    if (!is_finite(p)) throw Error(what + ": vertex " + std::to_string(i) + " has a non-finite position");
    char limit[32];
    std::snprintf(limit, sizeof limit, "%g", double(kMaxCoordinate));
    throw Error(what + ": vertex " + std::to_string(i) + " lies at (" + format_coordinates(p) +
                "), beyond the range +-" + limit + " that the scene supports");
  }
  for (size_t i = 0; i < nx.size(); ++i)
    if (!std::isfinite(nx[i]) || !std::isfinite(ny[i]) || !std::isfinite(nz[i]))
      throw Error(what + ": vertex " + std::to_string(i) + " has a non-finite normal");
  for (size_t i = 0; i < u.size(); ++i)
    if (!std::isfinite(u[i]) || !std::isfinite(v[i]))
      throw Error(what + ": vertex " + std::to_string(i) + " has a non-finite uv (" + format_number(u[i]) + ", " +
                  format_number(v[i]) + ")");
}

int64_t TriangleMesh::vertex_out_of_range() const {
  for (size_t i = 0; i < vertex_count(); ++i) {
    const Vec3f p = position(uint32_t(i));
    if (!is_finite(p) || !in_coordinate_range(p)) return int64_t(i);
  }
  return -1;
}

std::string format_coordinates(Vec3f p) {
  return format_number(p.x) + ", " + format_number(p.y) + ", " + format_number(p.z);
}

size_t TriangleMesh::own_bytes() const {
  return (x.size() + y.size() + z.size() + nx.size() + ny.size() + nz.size() + u.size() + v.size()) * sizeof(float) +
         indices.size() * sizeof(uint32_t);
}

TriangleMesh make_placed(std::shared_ptr<const TriangleMesh> source, const Transform& t) {
  if (!source || source->placed()) throw Error("internal: a placed mesh needs a source that is not placed");
  TriangleMesh m;
  m.nx = source->nx, m.ny = source->ny, m.nz = source->nz;
  if (t.determinant3() < 0) m.indices = source->indices;  // transform() swaps their winding
  m.transform(t);  // normals (and a mirror's triples); positions are the source's
  m.source = std::move(source);
  m.to_world = t;
  return m;
}

void TriangleMesh::transform(const Transform& t) {
  if (t.is_identity()) return;
  if (placed()) throw Error("internal: a placed mesh is transformed by its placement");
  for (size_t i = 0; i < x.size(); ++i) {
    const Vec3f p = t.apply_point(position(i));
    x[i] = p.x; y[i] = p.y; z[i] = p.z;
  }
  // Normals map by the inverse transpose, all with one common scale and NOT renormalized per vertex: the
  // interpolated normal field then is exactly the transformed object-space one, so a mesh placed by an instance
  // (transformed after interpolation) shades like the same mesh transformed here. The common factor only keeps
  // magnitudes near 1 (exactly 1 under similarity transforms).
  const float scale = std::cbrt(std::fabs(t.determinant3()));
  for (size_t i = 0; i < nx.size(); ++i) {
    const Vec3f n = t.apply_normal(normal(i)) * scale;
    nx[i] = n.x; ny[i] = n.y; nz[i] = n.z;
  }
  // A mirroring transform reverses the winding; swap two indices so cross(e1, e2) still points outward.
  if (t.determinant3() < 0)
    for (size_t i = 0; i + 2 < indices.size(); i += 3) std::swap(indices[i + 1], indices[i + 2]);
}

Bounds3f TriangleMesh::triangle_bounds(size_t tri) const {
  Bounds3f b;
  const uint32_t* idx = triangle(tri);
  for (int k = 0; k < 3; ++k) b.extend(position(idx[k]));
  return b;
}

float TriangleMesh::triangle_area(size_t tri) const {
  const uint32_t* idx = triangle(tri);
  const Vec3f p0 = position(idx[0]), p1 = position(idx[1]), p2 = position(idx[2]);
  return 0.5f * length(cross(p1 - p0, p2 - p0));
}

TriangleMesh make_cube() {
  TriangleMesh m;
  // Each face: an axis, a side, and two tangent axes ordered so (t1 x t2) points outward.
  for (int axis = 0; axis < 3; ++axis)
    for (int side = -1; side <= 1; side += 2) {
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      const uint32_t base = uint32_t(m.vertex_count());
      const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& c : corners) {
        Vec3f p;
        p[axis] = float(side);
        p[a1] = c[0];
        p[a2] = c[1] * float(side);  // flipping the second tangent on the negative side keeps faces outward
        m.add_vertex(p);
        m.u.push_back(0.5f * (c[0] + 1));
        m.v.push_back(0.5f * (c[1] + 1));
      }
      m.add_triangle(base, base + 1, base + 2);
      m.add_triangle(base, base + 2, base + 3);
    }
  return m;
}

TriangleMesh make_polygon(const std::vector<Vec3f>& vertices) {
  if (vertices.size() < 3) throw Error("a polygon needs at least 3 vertices");
  TriangleMesh m;
  for (const Vec3f& p : vertices) m.add_vertex(p);
  for (uint32_t i = 1; i + 1 < vertices.size(); ++i) m.add_triangle(0, i, i + 1);
  return m;
}

}  // namespace torte
