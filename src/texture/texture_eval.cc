// TextureTable evaluation: one switch on the node kind, children by index. Float values are splatted
// (x = y = z) so arithmetic and colour results share one code path.
#include <algorithm>
#include <cmath>

#include "texture/color_map.h"
#include "texture/mapping.h"
#include "texture/texture.h"

namespace torte {

namespace {

inline TexValue splat(float v, float width = 0) { return {v, v, v, width}; }

// The world-space footprint radius in uv units: the larger of footprint / |dp/du| and footprint / |dp/dv|
// (0 when the footprint or both derivatives are unknown).
float uv_footprint(const TextureContext& ctx) {
  if (ctx.footprint <= 0) return 0;
  const float lu = length(ctx.dpdu), lv = length(ctx.dpdv);
  float w = 0;
  if (lu > 0) w = std::max(w, ctx.footprint / lu);
  if (lv > 0) w = std::max(w, ctx.footprint / lv);
  return std::isfinite(w) ? w : 0;
}

// floor(x) mod 2 without converting floats beyond int64's range (undefined behaviour): floats that large are even
// integers anyway. NaN counts as 0.
int64_t cell_parity(float x) {
  const float f = std::floor(x);
  if (std::fabs(f) < 4e18f) return int64_t(f) & 1;
  return 0;
}

}  // namespace

TexValue TextureTable::eval_node(int32_t index, const TextureContext& ctx, TexValue in) const {
  const TextureNode& n = nodes_[size_t(index)];
  switch (n.kind) {
    case TextureKind::Constant:
      return {n.f[0], n.f[1], n.f[2], 0};
    case TextureKind::Uv:
      return {ctx.uv.x * n.f[0] + n.f[2], ctx.uv.y * n.f[1] + n.f[3], 0, uv_footprint(ctx) * n.width_scale};
    case TextureKind::Spherical: {
      const Vec3f q = transforms_[size_t(n.extra)].apply_inverse_point(ctx.p);
      const Vec2f st = spherical_mapping(q);
      // An arc of length w on a sphere of radius r spans w / (pi r) in v (and more in u off the equator).
      const float r = length(q);
      const float w = r > 0 ? ctx.footprint * n.width_scale / (kPi * r) : 0;
      return {st.x, st.y, 0, w};
    }
    case TextureKind::Cylindrical: {
      const Vec3f q = transforms_[size_t(n.extra)].apply_inverse_point(ctx.p);
      const Vec2f st = cylindrical_mapping(q);
      return {st.x, st.y, 0, ctx.footprint * n.width_scale};
    }
    case TextureKind::Planar: {
      const Vec3f q = transforms_[size_t(n.extra)].apply_inverse_point(ctx.p);
      const Vec2f st = planar_mapping(q, Vec3f(n.f[0], n.f[1], n.f[2]), Vec3f(n.f[3], n.f[4], n.f[5]),
                                      Vec2f(n.f[6], n.f[7]));
      return {st.x, st.y, 0, ctx.footprint * n.width_scale};
    }
    case TextureKind::Xyz: {
      const Vec3f q = transforms_[size_t(n.extra)].apply_inverse_point(ctx.p);
      return {q.x, q.y, q.z, ctx.footprint * n.width_scale};
    }
    case TextureKind::Checker2:
    case TextureKind::Checker3: {
      const float s = n.f[0];
      int64_t parity = cell_parity(in.x * s) + cell_parity(in.y * s);
      if (n.kind == TextureKind::Checker3) parity += cell_parity(in.z * s);
      // Children are closed textures: they read the hit, not this node's input.
      return eval_node((parity & 1) == 0 ? n.a : n.b, ctx, TexValue{});
    }
    case TextureKind::Noise:
      return splat(noise_texture(n.noise, Vec3f(in.x, in.y, in.z)));
    case TextureKind::Image: {
      const Rgb c = images_[size_t(n.extra)]->lookup(Vec2f(in.x, in.y), in.width);
      if (n.output == ValueType::Float) return splat(c.r);  // image_scalar: Float values are splatted
      return {c.r, c.g, c.b, 0};
    }
    case TextureKind::Grayscale:
      return splat(in.x);
    case TextureKind::Spline: {
      const Rgb c = eval_spline(&knot_colors_[size_t(n.extra)], &knot_positions_[size_t(n.extra)], n.count,
                                n.flag != 0, in.x);
      return {c.r, c.g, c.b, 0};
    }
    case TextureKind::Add: {
      const TexValue a = eval_node(n.a, ctx, in), b = eval_node(n.b, ctx, in);
      return {a.x + b.x, a.y + b.y, a.z + b.z, 0};
    }
    case TextureKind::Multiply: {
      const TexValue a = eval_node(n.a, ctx, in), b = eval_node(n.b, ctx, in);
      return {a.x * b.x, a.y * b.y, a.z * b.z, 0};
    }
    case TextureKind::Scale: {
      const TexValue a = eval_node(n.a, ctx, in);
      return {a.x * n.f[0], a.y * n.f[0], a.z * n.f[0], 0};
    }
    case TextureKind::Lerp: {
      const float t = eval_node(n.a, ctx, in).x;
      const TexValue a = eval_node(n.b, ctx, in), b = eval_node(n.c, ctx, in);
      return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.z + (b.z - a.z) * t, 0};
    }
    case TextureKind::Compose:
      return eval_node(n.a, ctx, eval_node(n.b, ctx, in));
  }
  return {};
}

}  // namespace torte
