// A closed octahedron (6 vertices, 12 edges, 8 outward-facing triangles), shared by the mesh reader and
// subdivision tests.
#pragma once
#include "geometry/mesh.h"

namespace torte::test {

inline constexpr double kOcta[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
inline constexpr int kOctaTris[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                        {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};

inline TriangleMesh octahedron() {
  TriangleMesh m;
  for (const auto& p : kOcta) m.add_vertex({float(p[0]), float(p[1]), float(p[2])});
  for (const auto& t : kOctaTris) m.add_triangle(uint32_t(t[0]), uint32_t(t[1]), uint32_t(t[2]));
  return m;
}

}  // namespace torte::test
