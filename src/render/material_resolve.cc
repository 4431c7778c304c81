#include "render/material_resolve.h"

#include <cmath>

#include "core/rng.h"

namespace torte {

Vec3f bump_normal(const Scene& scene, const BumpParams& bump, const SurfaceHit& s, float footprint) {
  const TextureTable& tex = scene.textures;
  const TextureContext tc = texture_context(s, footprint);
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
