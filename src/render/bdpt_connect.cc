#include "render/bdpt_connect.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"
#include "light/light.h"
#include "light/sky.h"

namespace torte {

namespace {

// A surface vertex's BSDF towards wi, with the cosine folded in: camera subpaths f |wi.ns|; light subpaths
// f |wo.ns| |wi.ng| / |wo.ng| (the adjoint shading-normal factor times the shading cosine, as shade_light.h),
// and the solid-angle densities of sampling wi given wo (pdf) and wo given wi (rev).
struct VertexEval {
  Rgb f;
  float pdf = 0, rev = 0;
};

bool eval_vertex(const BdptStore& store, const BdptVertex& v, Vec3f wi, bool importance, VertexEval* out) {
  if (!v.connectible) return false;
  const Frame frame = Frame::from_z(v.ns);
  const Vec3f wo_l = frame.to_local(v.wo), wi_l = frame.to_local(wi);
  if (!consistent_sides(v.ng, v.wo, wi, wo_l, wi_l)) return false;
  store.with_bsdf(v, [&](const auto& b) {
    out->f = b.eval(wo_l, wi_l);
    out->pdf = b.pdf(wo_l, wi_l);
    out->rev = b.pdf(wi_l, wo_l);
  });
  float c = std::fabs(wi_l.z);
  if (importance) {
    const float cos_g_wo = std::fabs(dot(v.wo, v.ng));
    if (!(cos_g_wo > 0)) return false;
    c = std::fabs(wo_l.z) * std::fabs(dot(wi, v.ng)) / cos_g_wo;
  }
  out->f = out->f * c;
  return !out->f.is_black() && out->f.is_finite();
}

// Solid-angle density of emission sampling (light_emission.cc) leaving a point of `light` (normal n on its
// emitting side) in direction w.
float emission_pdf_dir(const Light& light, Vec3f n, Vec3f w) {
  switch (light.kind) {
    case LightKind::Point: return uniform_sphere_pdf();
    case LightKind::Spot: return dot(w, light.direction) > light.cos_total ? cone_pdf_1mc(1 - light.cos_total) : 0;
    case LightKind::Area: {
      const float c = dot(n, w);
      if (light.two_sided) return 0.5f * std::fabs(c) * kInvPi;
      return c > 0 ? c * kInvPi : 0;
    }
    default: return 0;  // lights bdpt refuses (render_bdpt)
  }
}

bool point_like(const Light& light) { return light.kind == LightKind::Point || light.kind == LightKind::Spot; }

float remap0(float x) { return x != 0 ? x : 1; }

void push_connection(ShadowQueue& shadows, const BdptVertex& from, Vec3f wi, Vec3f to, Vec3f to_ng, Rgb value,
                     uint32_t path) {
  if (value.is_black() || !value.is_finite()) return;
  const Vec3f o = offset_origin(from.p, from.ng, wi);
  // Both ends are moved off their surfaces (the far one towards o) and the ray stops 1e-3 short: the traversal's
  // hit distances err by up to a few 1e-4 (relative) on long rays, so stopping 1e-4 short of a point on a surface
  // let that surface occlude it (the Cornell box's block tops lost a fifth of the ceiling's indirect light to
  // bdpt's connections; with the end offset alone, a sixteenth; bench/RESULTS.md 2026-12-04).
  // Aimed at the target from o (ray_towards: along wi the offset would shift the ray sideways).
  const Ray r = ray_towards(o, offset_origin(to, to_ng, -wi), wi, 1e-3f);
  shadows.push(r.o, r.d, r.t_max, value, path);
}

}  // namespace

void BdptConnector::load_densities(const BdptStore& light, const BdptStore& camera) {
  const size_t nl = std::max<size_t>(lchain_.size(), 1), nc = cchain_.size();
  lf_.assign(nl, 0);
  lr_.assign(nl, 0);
  ld_.assign(nl, 0);
  cf_.resize(nc);
  cr_.resize(nc);
  cd_.resize(nc);
  for (size_t j = 0; j < lchain_.size(); ++j) {
    const BdptVertex& v = light.vertices[lchain_[j]];
    lf_[j] = v.pdf_fwd;
    lr_[j] = v.pdf_rev;
    ld_[j] = v.delta;
  }
  for (size_t j = 0; j < nc; ++j) {
    const BdptVertex& v = camera.vertices[cchain_[j]];
    cf_[j] = v.pdf_fwd;
    cr_[j] = v.pdf_rev;
    cd_[j] = v.delta;
  }
}

double BdptConnector::own_merge_term(int s) const {
  if (!(rules_.eta > 0) || s < 2 || ld_[size_t(s - 1)]) return 0;
  const double m = rules_.eta * double(remap0(lr_[size_t(s - 1)]));
  return m * m;
}

double BdptConnector::mis_sum(int s, int t, bool light_delta) const {
  // Ratios of the other strategies' densities to this one's, built up one vertex at a time (pbrt's remapping:
  // no product of densities is ever formed, so none overflows); squared for the power heuristic. Merging at
  // the last light vertex of the connection strategy with sj light vertices has that strategy's density times
  // eta times the camera subpath's density of that vertex (Georgiev et al. 2012, sec. 4.2); only sj >= 2.
  const double eta = rules_.eta;
  auto vc_on = [&](int sj) { return rules_.connect || sj == 0; };
  auto merge_term = [&](double r, float pcam, int sj) {
    if (!(eta > 0) || sj < 2) return 0.0;
    const double m = eta * double(remap0(pcam));
    return r * m * m;
  };
  double sum = (vc_on(s) ? 1.0 : 0.0) + own_merge_term(s), r = 1;
  for (int i = t - 1; i > 0; --i) {
    const double q = double(remap0(cr_[size_t(i)])) / double(remap0(cf_[size_t(i)]));
    r *= q * q;
    const int sj = s + t - i;
    if (!cd_[size_t(i)] && !cd_[size_t(i - 1)] && vc_on(sj)) sum += r;
    if (!cd_[size_t(i)]) sum += merge_term(r, cf_[size_t(i)], sj);
  }
  r = 1;
  for (int i = s - 1; i >= 0; --i) {
    const double q = double(remap0(lr_[size_t(i)])) / double(remap0(lf_[size_t(i)]));
    r *= q * q;
    const bool prev_delta = i > 0 ? bool(ld_[size_t(i - 1)]) : light_delta;
    if (!ld_[size_t(i)] && !prev_delta && vc_on(i)) sum += r;
    if (i >= 2 && !ld_[size_t(i - 1)]) sum += merge_term(r, lr_[size_t(i - 1)], i);
  }
  return sum;
}

double BdptConnector::mis_weight(int s, int t, bool light_delta) const {
  if (s + t == 2) return 1;
  return 1 / mis_sum(s, t, light_delta);
}

void BdptConnector::connect(uint32_t path, const BdptStore& light, uint32_t light_path, const BdptStore& camera,
                            PathState& camera_paths, ShadowQueue& shadows, CameraQueue& splats) {
  light.chain(light_path, lchain_);
  camera.chain(path, cchain_);
  const int nl = int(lchain_.size()), nc = int(cchain_.size());
  for (int t = 1; t <= nc; ++t)
    for (int s = 0; s <= std::max(nl, 1); ++s) {
      const int depth = s + t - 2;
      if ((s == 1 && t == 1) || depth < 0 || depth > rules_.max_depth || (s >= 2 && s > nl)) continue;
      if (rules_.only_s >= 0 && (s != rules_.only_s || t != rules_.only_t)) continue;
      if (!rules_.connect && s != 0) continue;
      strategy(s, t, path, light, camera, camera_paths, shadows, splats);
    }
}

void BdptConnector::strategy(int s, int t, uint32_t path, const BdptStore& light, const BdptStore& camera,
                             PathState& camera_paths, ShadowQueue& shadows, CameraQueue& splats) {
  load_densities(light, camera);
  const uint32_t px = camera_paths.pixel[path], si = camera_paths.sample[path];
  const size_t sl = size_t(std::max(s - 1, 0)), tc = size_t(t - 1);  // the connecting vertices' positions
  const bool light_delta = !lchain_.empty() && point_like(scene_.lights[size_t(light.vertices[lchain_[0]].light)]);

  if (s == 0) {  // the camera subpath found an emitter
    const BdptVertex& v = camera.vertices[cchain_[tc]];
    if (v.light < 0) return;
    const Light& l = scene_.lights[size_t(v.light)];
    if (!(l.two_sided || dot(v.ng, v.wo) > 0)) return;  // area_emission: the emitting side only
    const Rgb value = v.beta * l.radiance;
    if (value.is_black()) return;
    cr_[tc] = scene_.light_selection.pmf(v.light) * v.pdf_emit;
    cd_[tc] = 0;
    if (t >= 3) cr_[tc - 1] = to_area_density(emission_pdf_dir(l, v.ng, v.wo), v.p, camera.vertices[cchain_[tc - 1]]);
    const Rgb weighted = value * float(mis_weight(0, t, false));
    if (weighted.is_finite()) camera_paths.radiance[path] += weighted;
    return;
  }

  if (t == 1) {  // a light subpath vertex connected to the camera: a splat
    const BdptVertex& q = light.vertices[lchain_[sl]];
    if (!q.connectible) return;
    CameraWiSample cs;
    const Vec2f u = sampler_.get_2d(px, si, kDimLightSubpathBase + bounce_dim(uint16_t(s - 2), kDimLightPoint));
    if (!camera_.sample_wi(q.p, u, &cs)) return;
    VertexEval e;
    if (!eval_vertex(light, q, cs.wi, true, &e)) return;
    const Rgb value = q.beta * e.f * (cs.we / cs.pdf);
    float pdf_pos, pdf_dir;
    camera_.pdf_we(Ray{cs.lens, -cs.wi}, &pdf_pos, &pdf_dir);
    lr_[sl] = to_area_density(pdf_dir, cs.lens, q);
    ld_[sl] = 0;
    lr_[sl - 1] = to_area_density(e.rev, q.p, light.vertices[lchain_[sl - 1]]);
    const Rgb weighted = value * float(mis_weight(s, 1, light_delta));
    if (weighted.is_black() || !weighted.is_finite()) return;
    const Vec3f o = offset_origin(q.p, q.ng, cs.wi);
    splats.push(o, cs.wi, length(q.p + cs.wi * cs.distance - o) * (1 - 1e-4f), weighted, path, cs.raster);
    return;
  }

  const BdptVertex& v = camera.vertices[cchain_[tc]];
  if (!v.connectible) return;
  if (s == 1) {  // light sampling at a camera vertex: a new light vertex, chosen as the light subpaths choose theirs
    const uint16_t depth = uint16_t(t - 2);
    float pmf;
    const int li = scene_.light_selection.sample_discrete(sampler_.get_1d(px, si, bounce_dim(depth, kDimLightSelect)),
                                                          &pmf);
    if (!(pmf > 0)) return;
    const Light& l = scene_.lights[size_t(li)];
    const Vec2f u = sampler_.get_2d(px, si, bounce_dim(depth, kDimLightPoint));
    BdptVertex lv;
    lv.kind = BdptVertexKind::Light;
    Vec3f wi;
    Rgb arriving;  // radiance arriving at v over the density of the light vertex (as a solid angle at v)
    if (l.kind == LightKind::Area) {
      float pdf_area;
      sample_area_light_point(scene_, l, u, &lv.p, &lv.ng, &pdf_area);
      const Vec3f d = lv.p - v.p;
      const float d2 = length_squared(d);
      if (!(pdf_area > 0) || !(d2 > 0)) return;
      wi = d / std::sqrt(d2);
      const float cos_l = dot(lv.ng, -wi);
      if (!(l.two_sided ? cos_l != 0 : cos_l > 0)) return;
      arriving = l.radiance * (std::fabs(cos_l) / (d2 * pdf_area * pmf));
      lv.pdf_fwd = pmf * pdf_area;
    } else {
      LightSample ls;
      if (!sample_light(scene_, l, v.p, u, &ls)) return;
      wi = ls.wi;
      lv.p = l.position;
      arriving = ls.radiance / pmf;
      lv.pdf_fwd = pmf;
    }
    VertexEval e;
    if (!eval_vertex(camera, v, wi, false, &e)) return;
    const Rgb value = v.beta * e.f * arriving;
    lf_[0] = lv.pdf_fwd;
    lr_[0] = to_area_density(e.pdf, v.p, lv);
    ld_[0] = 0;
    cr_[tc] = to_area_density(emission_pdf_dir(l, lv.ng, -wi), lv.p, v);
    cd_[tc] = 0;
    if (t >= 3) cr_[tc - 1] = to_area_density(e.rev, v.p, camera.vertices[cchain_[tc - 1]]);
    push_connection(shadows, v, wi, lv.p, lv.ng, value * float(mis_weight(1, t, point_like(l))), path);
    return;
  }

  // s >= 2, t >= 2: a light subpath vertex q and a camera subpath vertex v, joined by a shadow ray.
  const BdptVertex& q = light.vertices[lchain_[sl]];
  if (!q.connectible) return;
  const Vec3f d = q.p - v.p;
  const float d2 = length_squared(d);
  if (!(d2 > 0)) return;
  const Vec3f w = d / std::sqrt(d2);  // from v towards q
  VertexEval ev, eq;
  if (!eval_vertex(camera, v, w, false, &ev) || !eval_vertex(light, q, -w, true, &eq)) return;
  const Rgb value = v.beta * ev.f * eq.f * q.beta / d2;
  lr_[sl] = to_area_density(ev.pdf, v.p, q);
  ld_[sl] = 0;
  cr_[tc] = to_area_density(eq.pdf, q.p, v);
  cd_[tc] = 0;
  if (t >= 3) cr_[tc - 1] = to_area_density(ev.rev, v.p, camera.vertices[cchain_[tc - 1]]);
  lr_[sl - 1] = to_area_density(eq.rev, q.p, light.vertices[lchain_[sl - 1]]);
  push_connection(shadows, v, w, q.p, q.ng, value * float(mis_weight(s, t, light_delta)), path);
}

int BdptConnector::begin_merges(uint32_t path, const BdptStore& camera) {
  camera.chain(path, cchain_);
  return int(cchain_.size());
}

Rgb BdptConnector::merge(int tc, const BdptStore& camera, const BdptStore& photons, uint32_t photon) {
  const BdptVertex& y = camera.vertices[cchain_[size_t(tc)]];
  const BdptVertex& x = photons.vertices[photon];
  lchain_.clear();
  for (uint32_t v = photon; v != BdptVertex::kNone; v = photons.vertices[v].prev) lchain_.push_back(v);
  std::reverse(lchain_.begin(), lchain_.end());
  const int s = int(lchain_.size());  // the path as connection (s, tc): light vertices 0..s-1, camera 0..tc-1
  if (s < 2 || tc < 1 || !y.connectible || !x.connectible || s + tc - 2 > rules_.max_depth) return Rgb(0);
  // y's BSDF (radiance mode) towards the photon's incoming direction, without the cosine: the photon's
  // throughput is already a flux per area.
  const Frame frame = Frame::from_z(y.ns);
  const Vec3f wo_l = frame.to_local(y.wo), wi_l = frame.to_local(x.wo);
  if (!consistent_sides(y.ng, y.wo, x.wo, wo_l, wi_l)) return Rgb(0);
  Rgb f;
  float pdf = 0, rev = 0;
  camera.with_bsdf(y, [&](const auto& b) {
    f = b.eval(wo_l, wi_l);
    pdf = b.pdf(wo_l, wi_l);
    rev = b.pdf(wi_l, wo_l);
  });
  const Rgb value = y.beta * f * x.beta;
  if (value.is_black() || !value.is_finite()) return Rgb(0);
  load_densities(photons, camera);
  const size_t sl = size_t(s - 1), c = size_t(tc - 1);
  lr_[sl] = y.pdf_fwd;  // the camera subpath's density of the merged vertex
  ld_[sl] = 0;
  lr_[sl - 1] = to_area_density(pdf, x.p, photons.vertices[lchain_[sl - 1]]);
  if (tc >= 2) cr_[c] = to_area_density(rev, y.p, camera.vertices[cchain_[c]]);
  const bool light_delta = point_like(scene_.lights[size_t(photons.vertices[lchain_[0]].light)]);
  const double w = own_merge_term(s) / mis_sum(s, tc, light_delta);
  return value * float(w);
}

}  // namespace torte
