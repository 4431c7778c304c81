#include "geometry/surface_hit.h"

#include <algorithm>
#include <cmath>

namespace torte {

SurfaceHit triangle_surface(const TriangleMesh& mesh, const uint32_t* idx, const Vec3f p[3], float b1, float b2,
                            uint32_t object) {
  SurfaceHit s;
  s.object = object;
  const Vec3f p0 = p[0], p1 = p[1], p2 = p[2];
  const float b0 = 1 - b1 - b2;
  // Interpolating the vertices is more accurate than o + t d far from the origin.
  s.p = p0 * b0 + p1 * b1 + p2 * b2;
  const Vec3f e1 = p1 - p0, e2 = p2 - p0, c = cross(e1, e2);
  s.ng = normalize(c);
  s.ns = s.ng;
  if (mesh.has_normals()) {
    const Vec3f n = mesh.normal(idx[0]) * b0 + mesh.normal(idx[1]) * b1 + mesh.normal(idx[2]) * b2;
    if (length_squared(n) > 0) {
      s.ns = normalize(n);
      // Vertex normals state which side is the front: the geometric normal follows them (as in pbrt).
      s.ng = face_forward(s.ng, s.ns);
    }
  }
  if (!mesh.has_uvs()) {
    // The fixed parameterization (0,0), (1,0), (1,1) of every triangle: uv = (b1 + b2, b2), and pbrt's
    // construction below reduces to dp/du = p1 - p0, dp/dv = p2 - p1 (no division per hit).
    s.uv = Vec2f(b1 + b2, b2);
    s.dpdu = e1;
    s.dpdv = p2 - p1;
    if (!(length_squared(c) > 0)) {  // degenerate triangle: any tangent frame
      const Frame f = Frame::from_z(s.ng);
      s.dpdu = f.s;
      s.dpdv = f.t;
    }
    return s;
  }
  const Vec2f t0 = mesh.uv(idx[0]), t1 = mesh.uv(idx[1]), t2 = mesh.uv(idx[2]);
  s.uv = t0 * b0 + t1 * b1 + t2 * b2;
  // dp/du and dp/dv from the triangle's edges in position and uv (pbrt's construction).
  const Vec2f duv02 = t0 - t2, duv12 = t1 - t2;
  const Vec3f dp02 = p0 - p2, dp12 = p1 - p2;
  const float det = duv02.x * duv12.y - duv02.y * duv12.x;
  if (std::fabs(det) > 1e-12f) {
    s.dpdu = (dp02 * duv12.y - dp12 * duv02.y) / det;
    s.dpdv = (dp12 * duv02.x - dp02 * duv12.x) / det;
  }
  if (!(length_squared(cross(s.dpdu, s.dpdv)) > 0)) {  // degenerate uvs: any tangent frame
    const Frame f = Frame::from_z(s.ng);
    s.dpdu = f.s;
    s.dpdv = f.t;
  }
  return s;
}

SurfaceHit quadric_surface(const Quadric& q, Vec2f uv, uint32_t object) {
  SurfaceHit s;
  s.object = object;
  const SurfacePoint sp = surface_at(q, uv);
  s.p = sp.p;
  s.ng = s.ns = sp.n;
  s.uv = sp.uv;
  // Tangents by central differences of the parameterization (quadrics are few; this is off the hot path of
  // triangle scenes). Poles and other degenerate points fall back to any frame around the normal.
  constexpr float h = 1e-3f;
  auto at = [&](float u, float v) { return surface_at(q, Vec2f(std::clamp(u, 0.0f, 1.0f), std::clamp(v, 0.0f, 1.0f))).p; };
  s.dpdu = (at(uv.x + h, uv.y) - at(uv.x - h, uv.y)) / (2 * h);
  s.dpdv = (at(uv.x, uv.y + h) - at(uv.x, uv.y - h)) / (2 * h);
  if (!(length_squared(cross(s.dpdu, s.dpdv)) > 1e-12f * length_squared(sp.p) + 1e-20f)) {
    const Frame f = Frame::from_z(s.ng);
    s.dpdu = f.s;
    s.dpdv = f.t;
  }
  return s;
}

}  // namespace torte
