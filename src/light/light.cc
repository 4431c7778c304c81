#include "light/light.h"

#include <cmath>

#include "scene/scene.h"

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

}  // namespace

Rgb area_emission(const Light& light, const SurfaceHit& hit, Vec3f w) {
  if (light.two_sided || dot(hit.ng, w) < 0) return light.radiance;
  return {};
}

bool sample_light(const Scene& scene, const Light& light, Vec3f p, Vec2f u, LightSample* s) {
  switch (light.kind) {
    case LightKind::Point: {
      const Vec3f d = light.position - p;
      const float dist2 = length_squared(d);
      if (dist2 == 0) return false;
      s->distance = std::sqrt(dist2);
      s->wi = d / s->distance;
      s->radiance = light.radiance / dist2;
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
    case LightKind::Area: {
      Vec3f q, n;
      float pdf_area;
      if (light.object < scene.meshes.size()) {
        const TriangleMesh& mesh = scene.meshes[light.object];
        float u_rest;
        const int tri = light.triangles.sample_discrete(u.x, nullptr, &u_rest);
        const uint32_t* idx = &mesh.indices[3 * size_t(tri)];
        const Vec3f p0 = mesh.position(idx[0]), p1 = mesh.position(idx[1]), p2 = mesh.position(idx[2]);
        const Vec3f b = sample_uniform_triangle(Vec2f(u_rest, u.y));
        q = p0 * b.x + p1 * b.y + p2 * b.z;
        n = normalize(cross(p1 - p0, p2 - p0));
        if (mesh.has_normals()) {
          const Vec3f ns = mesh.normal(idx[0]) * b.x + mesh.normal(idx[1]) * b.y + mesh.normal(idx[2]) * b.z;
          if (length_squared(ns) > 0) n = face_forward(n, ns);
        }
        pdf_area = 1 / light.area;  // triangle chosen by area, point uniform on it
      } else {
        const SurfacePoint sp = sample_area(scene.quadrics[light.object - scene.meshes.size()], u, &pdf_area);
        q = sp.p;
        n = sp.n;
      }
      const Vec3f d = q - p;
      const float dist = length(d);
      if (!(dist > 0)) return false;
      s->wi = d / dist;
      s->distance = dist;
      const float cos_l = dot(n, -s->wi);
      if (!light.two_sided && cos_l <= 0) return false;
      s->pdf = area_to_solid_angle(pdf_area, p, q, n);
      if (!(s->pdf > 0) || !std::isfinite(s->pdf)) return false;
      s->radiance = light.radiance;
      s->delta = false;
      return true;
    }
  }
  return false;
}

float light_pdf(const Scene& scene, const Light& light, Vec3f p, Vec3f wi, const SurfaceHit* hit, float t) {
  switch (light.kind) {
    case LightKind::Point: return 0;
    case LightKind::Infinite: return uniform_sphere_pdf();
    case LightKind::Area: {
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

float light_power(const Scene& scene, const Light& light) {
  switch (light.kind) {
    case LightKind::Point: return 4 * kPi * light.radiance.average();
    case LightKind::Infinite: return 4 * kPi * kPi * scene.radius() * scene.radius() * light.radiance.average();
    case LightKind::Area: return kPi * light.area * light.radiance.average() * (light.two_sided ? 2.0f : 1.0f);
  }
  return 0;
}

}  // namespace torte
