#include "render/material_resolve.h"

#include <cmath>

#include "core/rng.h"

namespace torte {

namespace {

// The normal a tangent-space normal map gives: its rgb as (n + 1) / 2 with n's x, y times `scale`, in the frame
// of the shading normal, dp/du made orthogonal to it, and the bitangent on dp/dv's side.
Vec3f mapped_normal(const TextureTable& tex, const BumpParams& bump, const SurfaceHit& s, const TextureContext& tc) {
  const Rgb c = tex.eval(bump.normal_map, tc);
  Vec3f nt(bump.scale * (2 * c.r - 1), bump.scale * (2 * c.g - 1), 2 * c.b - 1);
  Vec3f t = s.dpdu - s.ns * dot(s.ns, s.dpdu);
  if (!(length_squared(t) > 0)) return s.ns;  // no uv parameterisation: nothing to orient the map by
  t = normalize(t);
  Vec3f b = cross(s.ns, t);
  if (dot(b, s.dpdv) < 0) b = -b;
  const Vec3f n = t * nt.x + b * nt.y + s.ns * nt.z;
  const float len2 = length_squared(n);
  if (!(len2 > 0) || !std::isfinite(len2)) return s.ns;
  const Vec3f u = n / std::sqrt(len2);
  return dot(u, s.ns) > 0 ? u : s.ns;  // a map pointing below the surface is ignored
}

}  // namespace

Vec3f bump_normal(const Scene& scene, const BumpParams& bump, const SurfaceHit& s, float footprint) {
  const TextureTable& tex = scene.textures;
  const TextureContext tc = texture_context(s, footprint);
  if (bump.normal_mapped) return mapped_normal(tex, bump, s, tc);
  // Finite-difference steps in uv: about half the pixel footprint, or a small fixed step when it is unknown.
  auto step = [&](Vec3f dp) {
    const float len = length(dp);
    float d = (footprint > 0 && len > 0) ? 0.5f * footprint / len : 0.0f;
    if (!(d > 1e-5f)) d = 5e-4f;
    return std::min(d, 0.05f);
  };
  const float du = step(s.dpdu), dv = step(s.dpdv);
  TextureContext tu = tc, tv = tc;
  tu.p = s.p + s.dpdu * du;
  tu.uv = Vec2f(s.uv.x + du, s.uv.y);
  tv.p = s.p + s.dpdv * dv;
  tv.uv = Vec2f(s.uv.x, s.uv.y + dv);
  const float h = tex.eval(bump.height, tc) * bump.scale;
  const float hu = tex.eval(bump.height, tu) * bump.scale;
  const float hv = tex.eval(bump.height, tv) * bump.scale;
  // Derivatives of the displaced point p + h n (the dn/du term is left out: shading normals vary slowly).
  const Vec3f dpdu = s.dpdu + s.ns * ((hu - h) / du);
  const Vec3f dpdv = s.dpdv + s.ns * ((hv - h) / dv);
  Vec3f n = cross(dpdu, dpdv);
  const float len2 = length_squared(n);
  if (!(len2 > 0) || !std::isfinite(len2)) return s.ns;
  n = n / std::sqrt(len2);
  return dot(n, s.ns) < 0 ? -n : n;
}

}  // namespace torte
