#include "light/light_emission.h"

#include <cmath>

#include "core/sampling.h"
#include "geometry/quadric.h"

namespace torte {

namespace {

// Origin for light arriving from infinity along `dir`: a point on the disk of the scene's bounding sphere,
// perpendicular to dir, moved back by the radius so the ray starts outside the scene. Returns the disk's area.
float disk_origin(const EmitterView& scene, Vec3f dir, Vec2f u, Vec3f* origin) {
  const float r = std::max(scene.radius, 1e-6f);
  const Frame f = Frame::from_z(dir);
  const Vec2f d = sample_uniform_disk_concentric(u);
  *origin = scene.center + (f.s * d.x + f.t * d.y) * r - dir * (r * 1.001f);
  return kPi * r * r;
}

// A diffuse emitter's point q (normal n of its emitting side, density pdf_area) leaves light in a
// cosine-weighted direction; two-sided emitters pick their side with uc. Le cos / (pdf_area * cos/pi * side_pdf)
// = Le pi / (pdf_area side_pdf).
bool emit_diffuse(Vec3f q, Vec3f n, float pdf_area, bool two_sided, Rgb radiance, Vec2f u_dir, float uc,
                  EmissionSample* s) {
  if (!(pdf_area > 0) || !std::isfinite(pdf_area)) return false;
  float side_pdf = 1;
  if (two_sided) {
    side_pdf = 0.5f;
    if (uc < 0.5f) n = -n;
  }
  const Vec3f local = sample_cosine_hemisphere(u_dir);
  if (!(local.z > 0)) return false;
  s->origin = q;
  s->normal = n;
  s->dir = normalize(Frame::from_z(n).to_world(local));
  s->weight = radiance * (kPi / (pdf_area * side_pdf));
  s->pdf_pos = pdf_area;
  s->pdf_dir = side_pdf * local.z * kInvPi;
  return !s->weight.is_black();
}

}  // namespace

bool sample_emission(const EmitterView& scene, const Light& light, Vec2f u_pos, Vec2f u_dir, float uc,
                     EmissionSample* s) {
  s->normal = Vec3f(0, 0, 0);
  s->pdf_pos = s->pdf_dir = 1;
  switch (light.kind) {
    case LightKind::Point: {
      s->origin = light.position;
      s->dir = sample_uniform_sphere(u_dir);
      s->weight = light.radiance / uniform_sphere_pdf();
      s->pdf_dir = uniform_sphere_pdf();
      return !s->weight.is_black();
    }
    case LightKind::Spot: {
      float pdf;
      s->origin = light.position;
      s->dir = sample_spot_emission(light, u_dir, &pdf);
      if (!(pdf > 0) || !std::isfinite(pdf)) return false;
      s->weight = light.radiance * (spot_falloff(light, dot(s->dir, light.direction)) / pdf);
      s->pdf_dir = pdf;
      return !s->weight.is_black();
    }
    case LightKind::Distant: {
      s->dir = light.direction;
      const float disk = disk_origin(scene, s->dir, u_pos, &s->origin);
      s->weight = light.radiance * disk;
      s->pdf_pos = 1 / disk;
      return !s->weight.is_black();
    }
    case LightKind::Infinite:
    case LightKind::Environment:
    case LightKind::Sky: {
      Vec3f wi;  // direction towards the light
      float pdf;
      Rgb le;
      if (light.kind == LightKind::Infinite) {
        wi = sample_uniform_sphere(u_dir);
        pdf = uniform_sphere_pdf();
        le = light.radiance;
      } else if (light.kind == LightKind::Environment) {
        if (!light.environment->sampling.sample(u_dir, &wi, &pdf)) return false;
        le = light.environment->lookup(wi);
      } else {
        if (!light.sky->sample(u_dir, &wi, &pdf)) return false;
        le = light.sky->radiance(wi);
      }
      if (!(pdf > 0) || !std::isfinite(pdf)) return false;
      s->dir = -wi;
      const float disk = disk_origin(scene, s->dir, u_pos, &s->origin);
      s->weight = le * (disk / pdf);
      s->pdf_pos = 1 / disk;
      s->pdf_dir = pdf;
      return !s->weight.is_black();
    }
    case LightKind::Patches: {
      const PatchPoint pp = light.patches->sample(u_pos);
      return emit_diffuse(pp.q, pp.n, pp.pdf_area, pp.two_sided, pp.radiance, u_dir, uc, s);
    }
    case LightKind::Area: {
      Vec3f q, n;
      Vec2f uv;
      float pdf_area;
      sample_area_light_point(scene, light, u_pos, &q, &n, &pdf_area, &uv);
      return emit_diffuse(q, n, pdf_area, light.two_sided, area_radiance(scene, light, q, n, uv), u_dir, uc, s);
    }
  }
  return false;
}

}  // namespace torte
