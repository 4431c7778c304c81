// Midpoint subdivision (counts, shared midpoints, watertightness, displacement) and smooth vertex normals, on
// small meshes built here and on a real scan from ../shared/data/meshes.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "core/error.h"
#include "geometry/mesh_normals.h"
#include "geometry/ply.h"
#include "geometry/subdivide.h"
#include "octahedron.h"

using namespace torte;
using test::octahedron;

namespace {

// Undirected edges -> number of triangles using them.
std::map<std::pair<uint32_t, uint32_t>, int> edge_use(const TriangleMesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> e;
  for (size_t i = 0; i < m.indices.size(); i += 3)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.indices[i + k], b = m.indices[i + (k + 1) % 3];
      ++e[{std::min(a, b), std::max(a, b)}];
    }
  return e;
}

}  // namespace

TEST_CASE("subdivide: counts, shared midpoints, watertightness, interpolation", "[mesh_io]") {
  TriangleMesh octa = octahedron();
  for (size_t i = 0; i < octa.vertex_count(); ++i) {  // normals and uvs to interpolate
    octa.nx.push_back(octa.x[i]), octa.ny.push_back(octa.y[i]), octa.nz.push_back(octa.z[i]);
    octa.u.push_back(float(i)), octa.v.push_back(2.0f * float(i));
  }
  CHECK(subdivide(octa, 0).indices == octa.indices);
  TriangleMesh m = octa;
  for (int level = 1; level <= 4; ++level) {
    const size_t E = edge_use(m).size();
    const TriangleMesh next = subdivide(m, 1);
    CHECK(next.triangle_count() == 4 * m.triangle_count());
    CHECK(next.vertex_count() == m.vertex_count() + E);
    const auto edges = edge_use(next);
    for (const auto& [edge, uses] : edges) REQUIRE(uses == 2);  // closed: every edge in exactly two triangles
    CHECK(long(next.vertex_count()) - long(edges.size()) + long(next.triangle_count()) == 2);  // Euler
    m = next;
  }
  CHECK(m.triangle_count() == 8 * 256);
  CHECK(subdivide(octa, 4).indices == m.indices);
  // Level 1: each new vertex is the midpoint of its edge, with averaged uvs and the normalized normal sum.
  const TriangleMesh one = subdivide(octa, 1);
  for (size_t t = 0; t < octa.triangle_count(); ++t) {
    const uint32_t a = octa.indices[3 * t], b = octa.indices[3 * t + 1];
    const uint32_t ab = one.indices[12 * t + 1];  // first child is (a, ab, ca)
    CHECK(one.indices[12 * t] == a);
    CHECK(one.position(ab) == (octa.position(a) + octa.position(b)) * 0.5f);
    CHECK(one.u[ab] == 0.5f * (octa.u[a] + octa.u[b]));
    CHECK(length(one.normal(ab) - normalize(octa.normal(a) + octa.normal(b))) < 1e-6f);
    // Children keep the parent's orientation.
    const Vec3f n = cross(octa.position(b) - octa.position(a), octa.position(octa.indices[3 * t + 2]) - octa.position(a));
    for (int c = 0; c < 4; ++c) {
      const uint32_t* i = &one.indices[12 * t + 3 * c];
      CHECK(dot(cross(one.position(i[1]) - one.position(i[0]), one.position(i[2]) - one.position(i[0])), n) > 0);
    }
  }
  CHECK_THROWS_AS(subdivide(octa, -1), Error);
}

TEST_CASE("subdivide: displacement is deterministic and bounded", "[mesh_io]") {
  const TriangleMesh octa = octahedron();
  const TriangleMesh a = subdivide(octa, 3, 0.1f, 7), b = subdivide(octa, 3, 0.1f, 7);
  CHECK(a.x == b.x);
  CHECK(a.y == b.y);
  CHECK(a.z == b.z);
  CHECK(a.indices == b.indices);
  CHECK_FALSE(a.has_normals());
  const TriangleMesh c = subdivide(octa, 3, 0.1f, 8), flat = subdivide(octa, 3);
  CHECK(a.x != c.x);
  CHECK(a.indices == flat.indices);
  for (uint32_t i = 0; i < 6; ++i) CHECK(a.position(i) == octa.position(i));  // old vertices stay
  // Split at every edge (a triangle soup, as uv seams split vertices), the displaced surface stays closed: every
  // corner lands exactly where it does for the welded mesh.
  TriangleMesh soup;
  for (uint32_t i : octa.indices) soup.add_vertex(octa.position(i));
  for (uint32_t t = 0; t < 8; ++t) soup.add_triangle(3 * t, 3 * t + 1, 3 * t + 2);
  const TriangleMesh soup3 = subdivide(soup, 3, 0.1f, 7);
  REQUIRE(soup3.indices.size() == a.indices.size());
  bool together = true;
  for (size_t i = 0; i < a.indices.size(); ++i) together &= soup3.position(soup3.indices[i]) == a.position(a.indices[i]);
  CHECK(together);
  // A level-1 midpoint moves at most 0.1 x edge length (sqrt 2) along the interpolated normal (outward here).
  const TriangleMesh one = subdivide(octa, 1, 0.1f, 7), one_flat = subdivide(octa, 1);
  int moved = 0;
  for (uint32_t i = 6; i < one.vertex_count(); ++i) {
    const Vec3f d = one.position(i) - one_flat.position(i);
    CHECK(length(d) <= 0.1f * std::sqrt(2.0f) * 1.0001f);
    CHECK(length(cross(d, normalize(one_flat.position(i)))) < 1e-5f);  // along the outward direction
    moved += length(d) > 0;
  }
  CHECK(moved >= 10);
  // With vertex normals the output's normals are recomputed from the displaced surface.
  TriangleMesh with_n = octa;
  for (size_t i = 0; i < 6; ++i) with_n.nx.push_back(with_n.x[i]), with_n.ny.push_back(with_n.y[i]), with_n.nz.push_back(with_n.z[i]);
  const TriangleMesh dn = subdivide(with_n, 2, 0.1f, 7);
  REQUIRE(dn.has_normals());
  TriangleMesh recomputed = dn;
  compute_vertex_normals(recomputed);
  CHECK(recomputed.nx == dn.nx);
}

TEST_CASE("subdivide: a real scan grows by 4x per level with V + E vertices", "[mesh_io]") {
  const std::string path = std::string(TORTE_SHARED_DATA) + "/meshes/bunny/bun_zipper_res4.ply";
  if (!std::filesystem::exists(path)) {
    WARN("skipped: " << path << " is absent (shared test data not installed)");
    return;
  }
  const TriangleMesh m = read_ply(path);
  const TriangleMesh s = subdivide(m, 2, 0.05f, 1);
  const size_t E = edge_use(m).size();
  const TriangleMesh one = subdivide(m, 1);
  CHECK(one.vertex_count() == m.vertex_count() + E);
  CHECK(s.triangle_count() == 16 * m.triangle_count());
  CHECK(s.vertex_count() == one.vertex_count() + edge_use(one).size());
  // Boundary edges (used once) stay boundary edges, split in two; no edge is used by more triangles than before.
  size_t boundary = 0, boundary_after = 0;
  for (const auto& [e, n] : edge_use(m)) boundary += n == 1;
  for (const auto& [e, n] : edge_use(one)) boundary_after += n == 1;
  CHECK(boundary_after == 2 * boundary);
}

TEST_CASE("smooth normals: flat polygons keep the face normal, a closed octahedron gets radial normals",
          "[mesh][normals]") {
  TriangleMesh hex = make_polygon({{0, 0, 0}, {2, 0, 0}, {3, 1, 0}, {2, 2, 0}, {0, 2, 0}, {-1, 1, 0}});
  compute_smooth_normals(hex);
  REQUIRE(hex.has_normals());
  for (size_t i = 0; i < hex.vertex_count(); ++i) CHECK(hex.normal(uint32_t(i)).z == Approx(1.0f));

  // Octahedron with shared vertices, wound outward: by symmetry each vertex normal is its position.
  TriangleMesh oct;
  for (Vec3f p : {Vec3f(1, 0, 0), Vec3f(-1, 0, 0), Vec3f(0, 1, 0), Vec3f(0, -1, 0), Vec3f(0, 0, 1), Vec3f(0, 0, -1)})
    oct.add_vertex(p);
  const uint32_t faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const auto& f : faces) oct.add_triangle(f[0], f[1], f[2]);
  compute_smooth_normals(oct);
  for (uint32_t i = 0; i < 6; ++i) {
    const Vec3f n = oct.normal(i), p = oct.position(i);
    CHECK(dot(n, p) == Approx(1.0f).epsilon(1e-5));
  }
}

// Issue 25: mesh:save writes binary PLY that reads back to the same values, bit for bit.
