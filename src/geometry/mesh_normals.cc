#include "geometry/mesh_normals.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/memory_budget.h"

#include "core/interrupt.h"

namespace torte {

void compute_smooth_normals(TriangleMesh& mesh) {
  const size_t nv = mesh.vertex_count();
  reserve_memory(uint64_t(nv) * 2 * sizeof(Vec3f),
                 "smooth normals of " + std::to_string(nv) + " vertices");  // the sums and the normals
  std::vector<Vec3f> sum(nv);
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    if ((t & 0xffff) == 0) throw_if_interrupted("smoothing normals");
    const uint32_t* idx = &mesh.indices[3 * t];
    const Vec3f p[3] = {mesh.position(idx[0]), mesh.position(idx[1]), mesh.position(idx[2])};
    const Vec3f n = cross(p[1] - p[0], p[2] - p[0]);
    const float len = length(n);
    if (!(len > 0)) continue;
    const Vec3f unit = n / len;
    for (int k = 0; k < 3; ++k) {
      const Vec3f a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
      const float la = length(a), lb = length(b);
      if (!(la > 0 && lb > 0)) continue;
      const float angle = std::acos(std::clamp(dot(a, b) / (la * lb), -1.0f, 1.0f));
      sum[idx[k]] += unit * angle;
    }
  }
  mesh.nx.resize(nv);
  mesh.ny.resize(nv);
  mesh.nz.resize(nv);
  for (size_t i = 0; i < nv; ++i) {
    const float len = length(sum[i]);
    const Vec3f n = len > 0 ? sum[i] / len : Vec3f(0, 0, 1);
    mesh.nx[i] = n.x;
    mesh.ny[i] = n.y;
    mesh.nz[i] = n.z;
  }
}

}  // namespace torte
