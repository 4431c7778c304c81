// Watertight ray/triangle intersection after Woop, Benthin & Wald 2013 ("Watertight Ray/Triangle
// Intersection", JCGT 2(1)). The ray is turned into the +z axis of a sheared frame in which every vertex is
// transformed on its own; the 2D edge functions of an edge shared by two triangles then see exactly the same
// vertex coordinates and come out as exact negatives of each other, so a ray through the edge is inside (or on
// the edge of) at least one of the two.

// The argument above needs each edge function to be evaluated as fl(fl(a*b) - fl(c*d)). A fused multiply-add
// would round only one product, breaking the antisymmetry between the two triangles of an edge; keep the
// compiler from contracting (GCC contracts by default in C++ as soon as the target has FMA).
#include "core/no_fp_contract.h"  // before every other include

#include "geometry/triangle.h"

#include <cmath>

namespace torte {

bool intersect_triangle(const Ray& ray, Vec3f p0, Vec3f p1, Vec3f p2, TriangleHit* hit) {
  return intersect_triangle(WatertightRay(ray), ray.t_max, p0, p1, p2, hit);
}

bool intersect_triangle(const WatertightRay& wr, float t_max, Vec3f p0, Vec3f p1, Vec3f p2, TriangleHit* hit) {
  if (!wr.valid) return false;
  const int kx = wr.kx, ky = wr.ky, kz = wr.kz;
  const float sx = wr.sx, sy = wr.sy, sz = wr.sz;
  const Vec3f& o = wr.o;

  // Vertices relative to the ray origin, sheared so the ray runs along +z through (0, 0).
  const Vec3f a = p0 - o, b = p1 - o, c = p2 - o;
  const float ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
  const float bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
  const float cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];

  // Edge functions: u for edge p1-p2 (weight of p0), v for p2-p0, w for p0-p1.
  float u = cx * by - cy * bx;
  float v = ax * cy - ay * cx;
  float w = bx * ay - by * ax;
  // A float 0 may be a rounded non-zero: redo all three in double, where the products of floats are exact and
  // the one rounding of the difference keeps the sign (and exact zeros stay zero).
  if (u == 0 || v == 0 || w == 0) {
    u = float(double(cx) * double(by) - double(cy) * double(bx));
    v = float(double(ax) * double(cy) - double(ay) * double(cx));
    w = float(double(bx) * double(ay) - double(by) * double(ax));
  }
  // No culling: inside means all three on the same side. A zero edge function counts as inside for both
  // triangles of an edge, so rays through an edge or a vertex hit at least one triangle (possibly two).
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
  const float det = u + v + w;
  if (det == 0) return false;  // ray parallel to the triangle's plane, or a degenerate triangle

  const float az = sz * a[kz], bz = sz * b[kz], cz = sz * c[kz];
  const float t_scaled = u * az + v * bz + w * cz;
  // Range test before the division (t = t_scaled / det), as the paper does: most candidates fail here, and the
  // vector kernels then skip their division. The sign flip is exact; t_max * |det| may round either way, so the
  // quotient is checked again below.
  const float t_signed = det < 0 ? -t_scaled : t_scaled;
  if (!(t_signed > 0 && t_signed < t_max * std::fabs(det))) return false;  // also rejects NaN
  const float inv_det = 1.0f / det;
  const float t = t_scaled * inv_det;
  if (!(t > 0 && t < t_max)) return false;
  if (hit) {
    hit->t = t;
    hit->b1 = v * inv_det;
    hit->b2 = w * inv_det;
  }
  return true;
}

}  // namespace torte
