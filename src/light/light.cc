#include "light/light.h"

#include "texture/texture.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "geometry/quadric.h"
#include "geometry/surface_hit.h"

namespace torte {

namespace {

// Converts an area density at light point q (normal n) into a solid-angle density seen from p.
float area_to_solid_angle(float pdf_area, Vec3f p, Vec3f q, Vec3f n) {
  const Vec3f d = q - p;
  const float dist2 = length_squared(d);
  const float cos_l = std::fabs(dot(n, d)) / std::sqrt(dist2);
  if (cos_l <= 0) return 0;
  return pdf_area * dist2 / cos_l;
}

// Cone of a sphere light seen from p: false when p is inside (or on) the sphere, where area sampling is used.
bool sphere_cone(const Light& light, Vec3f p, float* one_minus_cos, float* dc) {
  const float r = light.sphere_radius;
  const float dc2 = length_squared(light.sphere_center - p);
  if (!(dc2 > r * r * 1.0001f)) return false;
  const float sin2 = r * r / dc2;
  const float cos_max = std::sqrt(std::max(0.0f, 1 - sin2));
  *one_minus_cos = sin2 / (1 + cos_max);  // 1 - cos without cancellation
  *dc = std::sqrt(dc2);
  return *one_minus_cos > 0;
}

bool sample_sphere_cone(const Light& light, Vec3f p, Vec2f u, LightSample* s) {
  float omc, dc;
  if (!sphere_cone(light, p, &omc, &dc)) return false;
  const Vec3f wc = (light.sphere_center - p) / dc;
  const Vec3f local = sample_cone_1mc(u, omc);
  const Vec3f wi = normalize(Frame::from_z(wc).to_world(local));
  // Distance to the near intersection along wi: dc cos(theta) - sqrt(r^2 - dc^2 sin^2(theta)).
  const float sin2 = local.x * local.x + local.y * local.y;
  const float r = light.sphere_radius;
  const float disc = std::max(0.0f, r * r - dc * dc * sin2);
  float t = dc * local.z - std::sqrt(disc);
  if (!(t > 0)) t = dc * local.z;  // grazing: the tangent point
  s->wi = wi;
  s->distance = t;
  s->pdf = cone_pdf_1mc(omc);
  s->radiance = light.radiance;
  s->delta = false;
  return std::isfinite(s->pdf) && s->pdf > 0;
}

}  // namespace

const SurfaceEmission* patch_emission(const EmitterView& scene, const SurfaceHit& hit) {
  if (hit.material < 0 || size_t(hit.material) >= scene.override_emission.size()) return nullptr;
  const SurfaceEmission& e = scene.override_emission[size_t(hit.material)];
  return e.light >= 0 ? &e : nullptr;
}

const SurfaceEmission* patch_emission_towards(const EmitterView& scene, const SurfaceHit& hit, Vec3f w) {
  const SurfaceEmission* e = patch_emission(scene, hit);
  return e && (e->two_sided || dot(hit.ng, w) < 0) ? e : nullptr;
}

Rgb area_radiance(const EmitterView& scene, const Light& light, Vec3f p, Vec3f n, Vec2f uv) {
  // A constant texture is folded into the parameter's value (1 for an untextured light).
  if (light.emission_texture.texture < 0 || !scene.textures) return light.radiance * light.emission_texture.value;
  const Rgb t = scene.textures->eval(light.emission_texture, TextureContext{p, n, uv, {}, {}, 0});
  // A texture graph may compute negative or non-finite values (arithmetic nodes): no light there.
  auto clean = [](float v) { return v > 0 && v < 3.4e38f ? v : 0.0f; };
  return light.radiance * Rgb(clean(t.r), clean(t.g), clean(t.b));
}

Rgb area_emission(const EmitterView& scene, const Light& light, const SurfaceHit& hit, Vec3f w) {
  if (light.two_sided || dot(hit.ng, w) < 0) return area_radiance(scene, light, hit.p, hit.ns, hit.uv);
  return {};
}

float spot_falloff(const Light& light, float cos_theta) {
  if (cos_theta >= light.cos_falloff_start) return 1;
  if (cos_theta <= light.cos_total) return 0;
  const float t = (cos_theta - light.cos_total) / (light.cos_falloff_start - light.cos_total);
  return t * t * (3 - 2 * t);
}

Vec3f sample_spot_emission(const Light& light, Vec2f u, float* pdf) {
  const float omc = 1 - light.cos_total;
  *pdf = cone_pdf_1mc(omc);
  return normalize(Frame::from_z(light.direction).to_world(sample_cone_1mc(u, omc)));
}

void prepare_sphere_light(const Quadric& q, Light* light) {
  if (light->emission_texture.texture >= 0) return;  // textured: sampled by area, where the point's uv is known
  light->sphere_cone = false;
  if (light->kind != LightKind::Area || q.kind != QuadricKind::Sphere) return;
  float scale;
  if (!is_similarity(q.to_world, &scale)) return;
  light->sphere_cone = true;
  light->sphere_center = q.to_world.apply_point({0, 0, 0});
  light->sphere_radius = q.radius * scale;
}

bool prepare_mesh_light(const TriangleMesh& mesh, Light* light) {
  std::vector<float> areas(mesh.triangle_count());
  double total = 0;
  for (size_t t = 0; t < areas.size(); ++t) total += areas[t] = mesh.triangle_area(t);
  if (!(total > 0)) return false;
  light->triangles = Distribution1D(areas);
  light->area = float(total);
  light->emitter_triangles.resize(areas.size());
  for (size_t t = 0; t < areas.size(); ++t) {
    const uint32_t* idx = mesh.triangle(t);
    const Vec3f p0 = mesh.position(idx[0]), e1 = mesh.position(idx[1]) - p0, e2 = mesh.position(idx[2]) - p0;
    const Vec3f c = cross(e1, e2);
    const float len = length(c);
    light->emitter_triangles[t] = {p0, e1, e2, len > 0 ? c / len : Vec3f{0, 0, 1}};  // zero area: never chosen
  }
  return true;
}

Rgb escaped_radiance(const Light& light, Vec3f dir) {
  switch (light.kind) {
    case LightKind::Infinite: return light.radiance;
    case LightKind::Environment: return light.environment->lookup(dir);
    case LightKind::Sky: return light.sky->radiance(dir);
    default: return {};
  }
}

void sample_area_light_point(const EmitterView& scene, const Light& light, Vec2f u, Vec3f* q, Vec3f* n,
                             float* pdf_area, Vec2f* uv) {
  if (light.object < scene.meshes.size()) {
    float u_rest;
    const int tri = light.triangles.sample_discrete(u.x, nullptr, &u_rest);
    const EmitterTriangle& t = light.emitter_triangles[size_t(tri)];
    const Vec3f b = sample_uniform_triangle(Vec2f(u_rest, u.y));
    *q = t.p0 + t.e1 * b.y + t.e2 * b.z;
    *n = t.n;
    *pdf_area = 1 / light.area;  // triangle chosen by area, point uniform on it
    const TriangleMesh& mesh = scene.meshes[light.object];
    const bool need_uv = uv && mesh.has_uvs();
    if (!mesh.has_normals() && !need_uv) {
      if (uv) *uv = Vec2f();
      return;
    }
    const uint32_t* idx = mesh.triangle(size_t(tri));
    if (mesh.has_normals()) {
      const Vec3f ns = mesh.normal(idx[0]) * b.x + mesh.normal(idx[1]) * b.y + mesh.normal(idx[2]) * b.z;
      if (length_squared(ns) > 0) *n = face_forward(*n, ns);
    }
    if (uv) *uv = need_uv ? mesh.uv(idx[0]) * b.x + mesh.uv(idx[1]) * b.y + mesh.uv(idx[2]) * b.z : Vec2f();
  } else {
    const SurfacePoint sp = sample_area(scene.quadrics[light.object - scene.meshes.size()], u, pdf_area);
    *q = sp.p;
    *n = sp.n;
    if (uv) *uv = sp.uv;
  }
}

bool sample_light(const EmitterView& scene, const Light& light, Vec3f p, Vec2f u, LightSample* s, uint32_t part) {
  switch (light.kind) {
    case LightKind::Point:
    case LightKind::Spot: {
      const Vec3f d = light.position - p;
      const float dist2 = length_squared(d);
      if (dist2 == 0) return false;
      s->distance = std::sqrt(dist2);
      s->wi = d / s->distance;
      float falloff = 1;
      if (light.kind == LightKind::Spot) {
        falloff = spot_falloff(light, dot(-s->wi, light.direction));
        if (falloff == 0) return false;
      }
      s->radiance = light.radiance * (falloff / dist2);
      s->pdf = 1;
      s->delta = true;
      return true;
    }
    case LightKind::Distant: {
      s->wi = -light.direction;
      s->distance = kInfinity;
      s->radiance = light.radiance;
      s->pdf = 1;
      s->delta = true;
      return true;
    }
    case LightKind::Infinite: {
      s->wi = sample_uniform_sphere(u);
      s->distance = kInfinity;
      s->radiance = light.radiance;
      s->pdf = uniform_sphere_pdf();
      s->delta = false;
      return true;
    }
    case LightKind::Environment:
    case LightKind::Sky: {
      const bool env = light.kind == LightKind::Environment;
      const bool ok = env ? light.environment->sampling.sample(u, &s->wi, &s->pdf) : light.sky->sample(u, &s->wi, &s->pdf);
      if (!ok) return false;
      s->distance = kInfinity;
      s->radiance = env ? light.environment->lookup(s->wi) : light.sky->radiance(s->wi);
      s->delta = false;
      return !s->radiance.is_black();
    }
    case LightKind::Patches: {
      const PatchPoint pp = part == kWholeLight ? light.patches->sample(u) : light.patches->sample_part(part, u);
      const Vec3f d = pp.q - p;
      const float dist = length(d);
      if (!(dist > 0)) return false;
      s->wi = d / dist;
      s->distance = dist;
      if (!pp.two_sided && dot(pp.n, -s->wi) <= 0) return false;
      s->pdf = area_to_solid_angle(pp.pdf_area, p, pp.q, pp.n);
      if (!(s->pdf > 0) || !std::isfinite(s->pdf)) return false;
      s->radiance = pp.radiance;
      s->delta = false;
      return true;
    }
    case LightKind::Area: {
      if (light.sphere_cone && sample_sphere_cone(light, p, u, s)) return true;
      Vec3f q, n;
      Vec2f uv;
      float pdf_area;
      sample_area_light_point(scene, light, u, &q, &n, &pdf_area, &uv);
      const Vec3f d = q - p;
      const float dist2 = length_squared(d), dist = std::sqrt(dist2);
      if (!(dist > 0)) return false;
      s->wi = d * (1 / dist);  // one division, not three (this runs once per shaded hit)
      s->distance = dist;
      const float cos_l = dot(n, -s->wi);
      if (!light.two_sided && cos_l <= 0) return false;
      s->pdf = pdf_area * dist2 / std::fabs(cos_l);  // area_to_solid_angle with the distance at hand
      if (!(s->pdf > 0) || !std::isfinite(s->pdf)) return false;
      s->radiance = area_radiance(scene, light, q, n, uv);
      s->delta = false;
      return true;
    }
  }
  return false;
}

float light_pdf(const EmitterView& scene, const Light& light, Vec3f p, Vec3f wi, const SurfaceHit* hit, float t) {
  switch (light.kind) {
    case LightKind::Point:
    case LightKind::Spot:
    case LightKind::Distant: return 0;
    case LightKind::Infinite: return uniform_sphere_pdf();
    case LightKind::Environment: return light.environment->sampling.pdf(wi);
    case LightKind::Sky: return light.sky->pdf(wi);
    case LightKind::Patches: {
      const SurfaceEmission* e = hit ? patch_emission(scene, *hit) : nullptr;
      if (!e) return 0;
      return area_to_solid_angle(light.patches->pdf_area(e->radiance, e->two_sided), p, p + wi * t, hit->ng);
    }
    case LightKind::Area: {
      if (light.sphere_cone) {
        float omc, dc;
        if (sphere_cone(light, p, &omc, &dc)) return cone_pdf_1mc(omc);
      }
      float pdf_area;
      if (light.object < scene.meshes.size()) {
        pdf_area = 1 / light.area;
      } else {
        const Quadric& q = scene.quadrics[light.object - scene.meshes.size()];
        pdf_area = torte::pdf_area(q, hit->uv);
      }
      return area_to_solid_angle(pdf_area, p, p + wi * t, hit->ng);
    }
  }
  return 0;
}

float patch_pdf_in_part(const Light& light, Vec3f p, Vec3f wi, const SurfaceHit& hit, float t, uint32_t* part) {
  *part = 0;
  if (light.kind != LightKind::Patches) return 0;
  const int64_t k = light.patches->find(hit.p);
  if (k < 0) return 0;
  *part = light.patches->part_of(size_t(k));
  return area_to_solid_angle(light.patches->pdf_area_in_part(size_t(k)), p, p + wi * t, hit.ng);
}

float light_power(const EmitterView& scene, const Light& light) {
  const float disk = kPi * scene.radius * scene.radius;  // cross-section of the scene's bounding sphere
  switch (light.kind) {
    case LightKind::Point: return 4 * kPi * light.radiance.average();
    case LightKind::Spot:
      return 2 * kPi * light.radiance.average() *
             ((1 - light.cos_falloff_start) + 0.5f * (light.cos_falloff_start - light.cos_total));
    case LightKind::Distant: return disk * light.radiance.average();
    case LightKind::Infinite: return 4 * kPi * disk * light.radiance.average();
    case LightKind::Environment: return disk * light.environment->integral;
    case LightKind::Sky: return disk * (light.sky->sky_integral + light.sky->sun_integral);
    case LightKind::Patches: return kPi * light.patches->weight();
    case LightKind::Area: return kPi * light.area * light.radiance.average() * (light.two_sided ? 2.0f : 1.0f);
  }
  return 0;
}

const char* light_kind_name(LightKind kind) {
  switch (kind) {
    case LightKind::Point: return "point";
    case LightKind::Area: return "area";
    case LightKind::Infinite: return "infinite";
    case LightKind::Spot: return "spot";
    case LightKind::Distant: return "directional";
    case LightKind::Environment: return "environment";
    case LightKind::Sky: return "sky";
    case LightKind::Patches: return "voxel emission";
  }
  return "?";
}

Light placed_light(const Light& light, const Transform& to_world) {
  Light out = light;
  switch (light.kind) {
    case LightKind::Point:
      out.position = to_world.apply_point(light.position);
      break;
    case LightKind::Spot:
      out.position = to_world.apply_point(light.position);
      out.direction = normalize(to_world.apply_vector(light.direction));
      break;
    case LightKind::Distant:
      out.direction = normalize(to_world.apply_vector(light.direction));
      break;
    default:
      throw Error(light_name(light) + " is in a group placed by an instance; " + light_kind_name(light.kind) +
                  " lights cannot be instanced, add it to the scene itself");
  }
  if (!is_finite(out.position) || !(length_squared(out.direction) > 0) || !is_finite(out.direction))
    throw Error(light_name(light) + ": an instance's transform takes it out of range (not finite, or singular)");
  return out;
}

std::string light_name(const Light& light) {
  if (!light.origin.empty()) return light.origin;
  const char* kind = light_kind_name(light.kind);
  return std::string(std::strchr("aeiou", kind[0]) ? "an " : "a ") + kind + " light";
}

}  // namespace torte
