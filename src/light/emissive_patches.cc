#include "light/emissive_patches.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace torte {

namespace {

Bounds3f patch_bounds(const EmissivePatch& k) {
  Bounds3f b;
  b.extend(k.p), b.extend(k.p + k.e1), b.extend(k.p + k.e2);
  if (!k.triangle) b.extend(k.p + k.e1 + k.e2);
  return b;
}

// Spreads the low 10 bits of v to every third bit (Morton codes).
uint32_t spread3(uint32_t v) {
  v &= 0x3ff;
  v = (v | v << 16) & 0x030000ff;
  v = (v | v << 8) & 0x0300f00f;
  v = (v | v << 4) & 0x030c30c3;
  v = (v | v << 2) & 0x09249249;
  return v;
}

int32_t cell_coord(float v, float size) {
  return int32_t(std::clamp(std::floor(v / size), -2.0e9f, 2.0e9f));
}

bool cell_less(int32_t ax, int32_t ay, int32_t az, int32_t bx, int32_t by, int32_t bz) {
  if (ax != bx) return ax < bx;
  if (ay != by) return ay < by;
  return az < bz;
}

}  // namespace

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
  const size_t n = patches_.size();
  per_part_ = (n + kMaxParts - 1) / kMaxParts;
  if (per_part_ > 1) {  // parts of neighbouring patches: Morton order of the patches' centres
    Bounds3f all;
    for (const EmissivePatch& k : patches_) all.extend(patch_bounds(k).center());
    const Vec3f d = all.diagonal();
    std::vector<std::pair<uint32_t, size_t>> order(n);
    for (size_t k = 0; k < n; ++k) {
      const Vec3f c = patch_bounds(patches_[k]).center();
      uint32_t code = 0;
      for (int a = 0; a < 3; ++a) {
        const float t = d[a] > 0 ? (c[a] - all.lo[a]) / d[a] : 0.0f;
        code |= spread3(uint32_t(std::clamp(t, 0.0f, 1.0f) * 1023)) << a;
      }
      order[k] = {code, k};
    }
    std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<EmissivePatch> sorted(n);
    for (size_t k = 0; k < n; ++k) sorted[k] = patches_[order[k].second];
    patches_.swap(sorted);
  }
  std::vector<float> w(n);
  total_weight_ = 0;
  for (size_t k = 0; k < n; ++k) {
    const EmissivePatch& p = patches_[k];
    w[k] = p.area * p.radiance.average() * (p.two_sided ? 2.0f : 1.0f);
    total_weight_ += w[k];
  }
  select_ = Distribution1D(w);

  const size_t parts = (n + per_part_ - 1) / per_part_;
  part_weight_.assign(parts, 0);
  part_cdf_.assign(n, 0);
  for (uint32_t j = 0; j < parts; ++j) {
    double sum = 0;
    for (size_t k = part_begin(j); k < part_end(j); ++k) sum += w[k];
    part_weight_[j] = float(sum);
    double run = 0;
    for (size_t k = part_begin(j); k < part_end(j); ++k) part_cdf_[k] = float((run += w[k]) / sum);
    part_cdf_[part_end(j) - 1] = 1;
  }

  // The hash grid: cells as large as the largest patch, so each patch touches at most 2 cells per axis.
  cell_size_ = 0;
  for (const EmissivePatch& k : patches_) {
    const Vec3f d = patch_bounds(k).diagonal();
    cell_size_ = std::max({cell_size_, d.x, d.y, d.z});
  }
  if (!(cell_size_ > 0) || !std::isfinite(cell_size_)) cell_size_ = 1;
  cells_.clear();
  for (size_t k = 0; k < n; ++k) {
    Bounds3f b = patch_bounds(patches_[k]);
    // Points a little off the patch still find it (find's tolerance is 1e-5 of the coordinates' size).
    const float slack = 1e-3f * cell_size_ + 2e-5f * std::max({std::fabs(b.lo.x), std::fabs(b.lo.y), std::fabs(b.lo.z),
                                                               std::fabs(b.hi.x), std::fabs(b.hi.y), std::fabs(b.hi.z)});
    b.lo = b.lo - Vec3f(slack, slack, slack);
    b.hi = b.hi + Vec3f(slack, slack, slack);
    for (int32_t x = cell_coord(b.lo.x, cell_size_); x <= cell_coord(b.hi.x, cell_size_); ++x)
      for (int32_t y = cell_coord(b.lo.y, cell_size_); y <= cell_coord(b.hi.y, cell_size_); ++y)
        for (int32_t z = cell_coord(b.lo.z, cell_size_); z <= cell_coord(b.hi.z, cell_size_); ++z)
          cells_.push_back({x, y, z, uint32_t(k)});
  }
  std::sort(cells_.begin(), cells_.end(), [](const Cell& a, const Cell& b) {
    if (a.x != b.x || a.y != b.y || a.z != b.z) return cell_less(a.x, a.y, a.z, b.x, b.y, b.z);
    return a.patch < b.patch;
  });
}

namespace {

PatchPoint point_on(const EmissivePatch& k, Vec2f v) {
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
  return s;
}

}  // namespace

PatchPoint EmissivePatches::sample(Vec2f u) const {
  float u_rest;
  const EmissivePatch& k = patches_[size_t(select_.sample_discrete(u.x, nullptr, &u_rest))];
  PatchPoint s = point_on(k, Vec2f(u_rest, u.y));
  s.pdf_area = pdf_area(k.radiance, k.two_sided);
  return s;
}

PatchPoint EmissivePatches::sample_part(uint32_t part, Vec2f u) const {
  const size_t begin = part_begin(part), end = part_end(part);
  size_t k = begin;
  float u_rest = u.x;
  if (end - begin > 1) {
    const auto it = std::upper_bound(part_cdf_.begin() + long(begin), part_cdf_.begin() + long(end) - 1, u.x);
    k = size_t(it - part_cdf_.begin());
    const float lo = k > begin ? part_cdf_[k - 1] : 0.0f, hi = part_cdf_[k];
    u_rest = hi > lo ? std::min((u.x - lo) / (hi - lo), 0x1.fffffep-1f) : 0.5f;
  }
  PatchPoint s = point_on(patches_[k], Vec2f(u_rest, u.y));
  s.pdf_area = pdf_area_in_part(k);
  return s;
}

float EmissivePatches::pdf_area_in_part(size_t k) const {
  const EmissivePatch& p = patches_[k];
  const float w = part_weight_[part_of(k)];
  return w > 0 ? p.radiance.average() * (p.two_sided ? 2.0f : 1.0f) / w : 0.0f;
}

int64_t EmissivePatches::find(Vec3f q) const {
  const int32_t x = cell_coord(q.x, cell_size_), y = cell_coord(q.y, cell_size_), z = cell_coord(q.z, cell_size_);
  auto it = std::lower_bound(cells_.begin(), cells_.end(), 0, [&](const Cell& c, int) {
    return cell_less(c.x, c.y, c.z, x, y, z);
  });
  // Tolerance for q off the patch: rounding of q's coordinates and of the patch's placement.
  const float scale = std::max({std::fabs(q.x), std::fabs(q.y), std::fabs(q.z), cell_size_});
  const float tol = 1e-5f * scale;
  int64_t best = -1;
  float best_dist = kInfinity;
  for (; it != cells_.end() && it->x == x && it->y == y && it->z == z; ++it) {
    const EmissivePatch& k = patches_[it->patch];
    const Vec3f d = q - k.p;
    const float off = std::fabs(dot(d, k.n));
    if (off > tol || off >= best_dist) continue;
    // q's coordinates (a, b) along e1, e2, from the 2x2 Gram matrix.
    const float g11 = dot(k.e1, k.e1), g12 = dot(k.e1, k.e2), g22 = dot(k.e2, k.e2);
    const float det = g11 * g22 - g12 * g12;
    if (!(det > 0)) continue;
    const float a = (g22 * dot(d, k.e1) - g12 * dot(d, k.e2)) / det;
    const float b = (g11 * dot(d, k.e2) - g12 * dot(d, k.e1)) / det;
    const float ea = tol / std::sqrt(g11), eb = tol / std::sqrt(g22);
    const bool inside = k.triangle ? a >= -ea && b >= -eb && a + b <= 1 + ea + eb
                                   : a >= -ea && b >= -eb && a <= 1 + ea && b <= 1 + eb;
    if (inside) best = int64_t(it->patch), best_dist = off;
  }
  return best;
}

}  // namespace torte
