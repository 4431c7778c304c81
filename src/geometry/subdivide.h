// 1-to-4 midpoint subdivision with an optional deterministic displacement, to grow a scanned mesh into a big,
// detailed-looking one (e.g. 100 k triangles -> 25.6 M in 4 levels).
#pragma once
#include <cstdint>

#include "geometry/mesh.h"

namespace torte {

// Each level splits every triangle (a, b, c) into four using the midpoints of its edges; triangles sharing an
// edge share its midpoint vertex, so a closed mesh stays closed and V' = V + E, T' = 4 T. Normals (normalized
// sum) and uvs (average) of midpoints are interpolated from the edge's end points.
//
// displacement != 0 moves each new vertex along the displacement normal by displacement x edge length x a
// hash-based random number in [-1, 1]. The random number depends on `seed`, the level and the positions of the
// edge's end points; the displacement normal is the input's area-weighted vertex normal, computed with vertices
// at equal positions welded and then interpolated like the other attributes. So vertices split at uv seams or
// normal creases move together (the surface does not tear), and the result depends on neither the thread count
// nor the timing.
// When the input has vertex normals and displacement != 0, the output's normals are recomputed from the
// displaced surface (area-weighted face normals), so shading shows the new detail.
//
// Throws torte::Error for levels < 0, an invalid input mesh, or a result over 2^31 triangles or the memory budget
// (both checked before the first level runs).
TriangleMesh subdivide(const TriangleMesh& mesh, int levels, float displacement = 0, uint64_t seed = 0);

constexpr uint64_t kMaxSubdividedTriangles = uint64_t(1) << 31;

// What subdivide(mesh, levels, ...) makes: triangles (UINT64_MAX past 2^31 x 4), vertices at most, and the most
// bytes one level holds at once (input, output and edge scratch).
struct SubdivisionSize {
  uint64_t triangles = 0, vertices = 0, peak_bytes = 0;
};
SubdivisionSize subdivision_size(const TriangleMesh& mesh, int levels, bool displaced);

// Area-weighted vertex normals from the triangles (zero for a vertex only on degenerate triangles).
void compute_vertex_normals(TriangleMesh& mesh);

}  // namespace torte
