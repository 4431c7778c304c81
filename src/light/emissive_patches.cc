#include "light/emissive_patches.h"

#include <cmath>

#include "core/error.h"

namespace torte {

void EmissivePatches::add_parallelogram(Vec3f p, Vec3f e1, Vec3f e2, Vec3f n, Rgb radiance, bool two_sided) {
  EmissivePatch k;
  k.p = p;
  k.e1 = e1;
  k.e2 = e2;
  k.n = normalize(n);
  k.radiance = radiance;
  k.area = length(cross(e1, e2));
  k.two_sided = two_sided;
  if (k.area > 0 && radiance.average() > 0) patches_.push_back(k);
}

void EmissivePatches::add_triangle(Vec3f p0, Vec3f p1, Vec3f p2, Rgb radiance, bool two_sided) {
  EmissivePatch k;
  k.p = p0;
  k.e1 = p1 - p0;
  k.e2 = p2 - p0;
  const Vec3f c = cross(k.e1, k.e2);
  k.area = 0.5f * length(c);
  if (!(k.area > 0) || !(radiance.average() > 0)) return;
  k.n = normalize(c);
  k.radiance = radiance;
  k.triangle = true;
  k.two_sided = two_sided;
  patches_.push_back(k);
}

void EmissivePatches::finish() {
  if (patches_.empty()) throw Error("emissive patches: nothing emits (zero area or black radiance)");
  std::vector<float> w(patches_.size());
  total_weight_ = 0;
  for (size_t k = 0; k < patches_.size(); ++k) {
    const EmissivePatch& p = patches_[k];
    w[k] = p.area * p.radiance.average() * (p.two_sided ? 2.0f : 1.0f);
    total_weight_ += w[k];
  }
  select_ = Distribution1D(w);
}

PatchPoint EmissivePatches::sample(Vec2f u) const {
  float u_rest;
  const EmissivePatch& k = patches_[size_t(select_.sample_discrete(u.x, nullptr, &u_rest))];
  const Vec2f v(u_rest, u.y);
  PatchPoint s;
  if (k.triangle) {
    const Vec3f b = sample_uniform_triangle(v);
    s.q = k.p + k.e1 * b.y + k.e2 * b.z;
  } else {
    s.q = k.p + k.e1 * v.x + k.e2 * v.y;
  }
  s.n = k.n;
  s.radiance = k.radiance;
  s.two_sided = k.two_sided;
  s.pdf_area = pdf_area(k.radiance, k.two_sided);
  return s;
}

}  // namespace torte
