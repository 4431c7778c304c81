// Smooth vertex normals for meshes that come without them (most scans: the Stanford PLYs): each vertex gets the
// average of its triangles' normals weighted by the triangle's angle at that vertex (Thürmer & Wüthrich 1998),
// which does not depend on how a surface happens to be triangulated.
#pragma once
#include "geometry/mesh.h"

namespace torte {

// Replaces mesh.nx/ny/nz. Vertices used by no (non-degenerate) triangle get the +z normal. Normals point to the
// winding-defined front side, so they agree with the geometric normals the renderer computes.
void compute_smooth_normals(TriangleMesh& mesh);

}  // namespace torte
