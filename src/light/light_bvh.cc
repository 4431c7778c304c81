#include "light/light_bvh.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "geometry/quadric.h"
#include "light/emissive_patches.h"
#include "simd/light_bvh_batch.h"

namespace torte {

namespace {

float safe_sqrt(float v) { return std::sqrt(std::max(v, 0.0f)); }
float safe_acos(float v) { return std::acos(std::clamp(v, -1.0f, 1.0f)); }

// cos(a - b) and sin(a - b) with the difference clamped at 0 (angles given by their sines and cosines).
float cos_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  return cos_a > cos_b ? 1.0f : cos_a * cos_b + sin_a * sin_b;
}
float sin_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  return cos_a > cos_b ? 0.0f : sin_a * cos_b - cos_a * sin_b;
}

Vec3f rotate(Vec3f v, Vec3f axis, float angle) {  // Rodrigues
  const Vec3f k = normalize(axis);
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

// pbrt-v4's orientation measure of a cone of normals widened by theta_e (the SAOH's M_Omega).
float orientation_measure(float cos_theta_o, float cos_theta_e) {
  const float theta_o = safe_acos(cos_theta_o), theta_e = safe_acos(cos_theta_e);
  const float theta_w = std::min(theta_o + theta_e, kPi);
  const float sin_o = std::sin(theta_o);
  return 2 * kPi * (1 - cos_theta_o) +
         kPi / 2 * (2 * theta_w * sin_o - std::cos(theta_o - 2 * theta_w) - 2 * theta_o * sin_o + cos_theta_o);
}

LightBounds merge(const LightBounds& a, const LightBounds& b) {
  if (a.phi == 0) return b;
  if (b.phi == 0) return a;
  LightBounds m;
  m.bounds = torte::merge(a.bounds, b.bounds);
  m.phi = a.phi + b.phi;
  m.normals = merge(a.normals, b.normals);
  m.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
  m.two_sided = a.two_sided || b.two_sided;
  return m;
}

// The normals of an area light's mesh triangles (their winding's side), or every direction for quadrics.
DirectionCone mesh_normals(const TriangleMesh& mesh) {
  Vec3f sum{0, 0, 0};
  std::vector<Vec3f> normals;
  normals.reserve(mesh.triangle_count());
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t* idx = mesh.triangle(t);
    const Vec3f p0 = mesh.position(idx[0]), p1 = mesh.position(idx[1]), p2 = mesh.position(idx[2]);
    const Vec3f n = cross(p1 - p0, p2 - p0);
    if (length_squared(n) == 0) continue;
    normals.push_back(normalize(n));
    sum = sum + normalize(n) * mesh.triangle_area(t);
  }
  if (normals.empty() || length_squared(sum) == 0) return DirectionCone::everywhere();
  const Vec3f w = normalize(sum);
  float cos_min = 1;
  for (const Vec3f& n : normals) cos_min = std::min(cos_min, dot(w, n));
  // A little slack for rounding: a cone that excludes a true normal would make a light unreachable.
  return {w, std::max(-1.0f, cos_min - 1e-4f), false};
}

}  // namespace

DirectionCone merge(const DirectionCone& a, const DirectionCone& b) {
  if (a.empty) return b;
  if (b.empty) return a;
  const float theta_a = safe_acos(a.cos_theta), theta_b = safe_acos(b.cos_theta);
  const float theta_d = safe_acos(dot(a.w, b.w));
  if (std::min(theta_d + theta_b, kPi) <= theta_a) return a;
  if (std::min(theta_d + theta_a, kPi) <= theta_b) return b;
  const float theta_o = (theta_a + theta_d + theta_b) / 2;
  if (theta_o >= kPi) return DirectionCone::everywhere();
  const float theta_r = theta_o - theta_a;
  const Vec3f axis = cross(a.w, b.w);
  if (length_squared(axis) < 1e-12f) return DirectionCone::everywhere();
  return {normalize(rotate(a.w, axis, theta_r)), std::cos(theta_o), false};
}

float LightBounds::importance(Vec3f p, Vec3f n, float min_d2) const {
  return phi > 0 ? LightBvh::importance(LightBvh::pack(*this), p, n, min_d2) : 0.0f;
}

LightBvh::PackedNode LightBvh::pack(const LightBounds& b) {
  PackedNode nd;
  nd.center = b.bounds.center();
  nd.phi = b.phi;
  nd.w = b.normals.w;
  nd.cos_o = b.normals.cos_theta;
  nd.diag2 = length_squared(b.bounds.diagonal());
  nd.cos_e = b.cos_theta_e;
  nd.part_bits = b.two_sided ? PackedNode::kTwoSided : 0;
  return nd;
}

float LightBvh::importance(const PackedNode& nd, Vec3f p, Vec3f n, float min_d2) {
  const float phi = nd.phi;
  if (phi <= 0) return 0;
  const Vec3f c = nd.center;
  // Clamp the distance at an eighth of the box's diagonal: inside or next to it the 1/d^2 falloff means nothing.
  // At half the diagonal (the first choice) a point inside a large box saw it as far away as its sibling's
  // centre, so the descent stayed uniform for the top levels (10,000 beads: 1.13x better than by power alone).
  const float dc2 = length_squared(p - c);
  const float d2 = std::max({dc2, nd.diag2 * (1.0f / 64), min_d2});
  if (d2 == 0) return phi;  // a point light at p itself
  const float r2 = nd.diag2 * 0.25f;  // the box's bounding sphere, squared
  const bool has_n = n.x != 0 || n.y != 0 || n.z != 0;
  if (nd.cos_o <= -1 && nd.cos_e < 1) {
    // Normals everywhere (spheres, points, and their groups): p lies inside the emission cone, only the distance
    // and the receiver's cosine count. The same value as below with fewer roots: 10,000 beads spent 15 % of
    // their render time here.
    if (!has_n || dc2 <= r2) return phi / d2;
    // The receiver's cosine bound cos(max(0, theta_i - theta_b)) with the angles' sines and cosines scaled by
    // the distance dc (cos_i = a / dc, cos_b = s_b / dc, sin_b = r / dc, sin_i = s_i / dc): one root fewer than
    // from the angles themselves.
    const float a = std::fabs(dot(p - c, n)), s_b = safe_sqrt(dc2 - r2);
    if (a > s_b) return phi / d2;
    const float s_i = safe_sqrt(dc2 - a * a), r = 0.5f * std::sqrt(nd.diag2);
    return phi / d2 * (std::max(0.0f, a * s_b + s_i * r) / dc2);  // (d2 * dc2 could overflow far away)
  }
  const Vec3f wi = normalize(p - c);
  float cos_w = dot(nd.w, wi);
  if (nd.part_bits & PackedNode::kTwoSided) cos_w = std::fabs(cos_w);
  const float sin_w = safe_sqrt(1 - cos_w * cos_w);
  // The cone of directions from p that reach the box: everything when p is inside its bounding sphere.
  const float cos_b = dc2 <= r2 ? -1.0f : safe_sqrt(1 - r2 / dc2), sin_b = safe_sqrt(1 - cos_b * cos_b);
  const float cos_o = nd.cos_o, sin_o = safe_sqrt(1 - cos_o * cos_o);
  // The angle between the emission cone and p, less the normal cone and the box's extent seen from p.
  const float cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, cos_o), sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, cos_o);
  const float cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
  if (cos_p <= nd.cos_e) return 0;
  float importance = phi * cos_p / d2;
  if (has_n) {  // the receiver's cosine, over the box's extent
    const float cos_i = std::fabs(dot(wi, n)), sin_i = safe_sqrt(1 - cos_i * cos_i);
    importance *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
  }
  return std::max(importance, 0.0f);
}

LightBounds light_bounds(const EmitterView& scene, const Light& light, float power, uint32_t part) {
  LightBounds b;
  if (light.kind == LightKind::Patches && part != kWholeLight) power = kPi * light.patches->part_weight(part);
  if (!(power > 0)) return b;
  switch (light.kind) {
    case LightKind::Point:
      b.bounds.extend(light.position);
      b.normals = DirectionCone::everywhere();
      b.cos_theta_e = std::cos(kPi / 2);
      break;
    case LightKind::Spot:
      b.bounds.extend(light.position);
      b.normals = {light.direction, 1, false};
      b.cos_theta_e = light.cos_total;  // no light leaves beyond the cone
      break;
    case LightKind::Area:
      if (light.object < scene.meshes.size()) {
        const TriangleMesh& mesh = scene.meshes[light.object];
        for (size_t t = 0; t < mesh.triangle_count(); ++t) b.bounds.extend(mesh.triangle_bounds(t));
        b.normals = mesh_normals(mesh);
      } else {
        b.bounds = world_bounds(scene.quadrics[light.object - scene.meshes.size()]);
        b.normals = DirectionCone::everywhere();
      }
      b.cos_theta_e = std::cos(kPi / 2);
      b.two_sided = light.two_sided;
      break;
    case LightKind::Patches: {
      const EmissivePatches& ps = *light.patches;
      const size_t begin = part == kWholeLight ? 0 : ps.part_begin(part);
      const size_t end = part == kWholeLight ? ps.size() : ps.part_end(part);
      for (size_t k = begin; k < end; ++k) {
        const EmissivePatch& q = light.patches->patch(k);
        b.bounds.extend(q.p), b.bounds.extend(q.p + q.e1), b.bounds.extend(q.p + q.e2);
        if (!q.triangle) b.bounds.extend(q.p + q.e1 + q.e2);
        b.normals = merge(b.normals, DirectionCone{q.n, 1, false});
        b.two_sided = b.two_sided || q.two_sided;
      }
      b.cos_theta_e = std::cos(kPi / 2);
      break;
    }
    default:
      return b;  // lights at infinity and directional lights: beside the BVH
  }
  if (b.bounds.empty()) return b;
  b.phi = power;
  return b;
}

LightBvh::LightBvh(const EmitterView& scene, std::span<const Light> lights, std::span<const float> power) {
  light_count_ = lights.size();
  in_bvh_.assign(lights.size(), 0);
  first_item_.assign(lights.size(), 0);
  item_count_.assign(lights.size(), 0);
  std::vector<LightBounds> all;
  std::vector<Item> items;
  std::vector<uint32_t> ids;
  for (size_t i = 0; i < lights.size(); ++i) {
    if (!(power[i] > 0)) continue;
    // A uniform infinite light is left to BSDF sampling, which samples its constant radiance as well as the BSDF
    // allows (pbrt-v4's allowIncompletePDF): never chosen here, pmf 0, so BSDF-sampled rays that escape carry its
    // light with MIS weight 1, and no light sample is spent on directions below the horizon.
    if (lights[i].kind == LightKind::Infinite) continue;
    if (is_infinite_light(lights[i]) || lights[i].kind == LightKind::Distant) {
      infinite_.push_back(uint32_t(i));
      in_bvh_[i] = 2;
      // Irradiance it gives a surface facing it, from light_power (light/light.cc): distant lights' power is
      // their irradiance over the scene's cross-section, the others' a sphere's worth of radiance over it. The
      // sky's is its dome's (half its integral, all above the horizon) plus the sun's at normal incidence: a
      // quarter of its integral, as for a uniform sphere, took half of the Minecraft daylight's samples.
      const float disk = kPi * scene.radius * scene.radius;
      if (lights[i].kind == LightKind::Sky)
        infinite_irradiance_ += lights[i].sky->sky_integral / 2 + lights[i].sky->sun_integral;
      else if (disk > 0)
        infinite_irradiance_ += power[i] / (lights[i].kind == LightKind::Distant ? disk : 4 * disk);
      continue;
    }
    const bool parts = lights[i].kind == LightKind::Patches;
    const uint32_t count = parts ? uint32_t(lights[i].patches->part_count()) : 1;
    first_item_[i] = uint32_t(items.size());
    item_count_[i] = count;
    for (uint32_t j = 0; j < count; ++j) {
      items.push_back({uint32_t(i), j});
      all.push_back(light_bounds(scene, lights[i], power[i], parts ? j : kWholeLight));
      if (all.back().phi > 0) ids.push_back(uint32_t(items.size() - 1)), in_bvh_[i] = 1;
    }
  }
  trail_.assign(items.size(), 0);
  if (!ids.empty()) {
    std::vector<Node> nodes;
    nodes.reserve(2 * ids.size());
    build(nodes, ids, 0, ids.size(), all, items, 0, 0);
    repack(nodes);
    if (!infinite_.empty()) build_grid(nodes[0].bounds.bounds);
  }
  if (ids.size() == 1 && infinite_.empty()) only_light_ = int(items[ids[0]].light), only_part_ = items[ids[0]].part;
}

void LightBvh::repack(const std::vector<Node>& nodes) {
  packed_.assign(nodes.size(), {});
  const auto pack_node = [&](uint32_t from, uint32_t to) {
    const Node& nd = nodes[from];
    packed_[to] = pack(nd.bounds);
    if (nd.leaf) packed_[to].index = nd.child_or_light, packed_[to].part_bits |= nd.part | PackedNode::kLeaf;
  };
  pack_node(0, 0);
  uint32_t next = 1;
  std::vector<std::pair<uint32_t, uint32_t>> stack{{0, 0}};  // (build index, packed index) of inner nodes
  while (!stack.empty()) {
    const auto [from, to] = stack.back();
    stack.pop_back();
    if (nodes[from].leaf) continue;
    const uint32_t a = from + 1, b = nodes[from].child_or_light;
    packed_[to].index = next;
    pack_node(a, next);
    pack_node(b, next + 1);
    stack.push_back({a, next});
    stack.push_back({b, next + 1});
    next += 2;
  }
}

float LightBvh::cut_irradiance(Vec3f c, float min_d2) const {
  // Barnes-Hut: a node whose box is small against its distance counts as a whole, else its children do.
  constexpr float kOpen2 = 0.5f * 0.5f;  // open nodes whose diagonal exceeds half their distance
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  double sum = 0;
  while (top > 0) {
    const PackedNode& nd = packed_[stack[--top]];
    if (nd.leaf() || nd.diag2 <= kOpen2 * length_squared(c - nd.center) || top + 2 > 64) {
      sum += importance(nd, c, {0, 0, 0}, min_d2);
      continue;
    }
    stack[top++] = nd.index + 1;
    stack[top++] = nd.index;
  }
  return float(sum / kPi);
}

void LightBvh::build_grid(const Bounds3f& r) {
  if (packed_.size() < 2) return;  // one light: the root's importance is its own
  const Vec3f e = r.diagonal();
  const float margin = 0.25f * std::max({e.x, e.y, e.z});
  if (!(margin > 0) || !std::isfinite(margin)) return;
  grid_box_ = r;
  grid_box_.lo = r.lo - Vec3f(margin, margin, margin);
  grid_box_.hi = r.hi + Vec3f(margin, margin, margin);
  const Vec3f g = grid_box_.diagonal();
  // Cubic cells, kGridCells of them at most.
  float cell = std::cbrt(g.x * g.y * g.z / float(kGridCells));
  for (;;) {
    for (int a = 0; a < 3; ++a) grid_n_[a] = std::max(1, int(std::ceil(g[a] / cell)));
    if (size_t(grid_n_[0]) * size_t(grid_n_[1]) * size_t(grid_n_[2]) <= kGridCells) break;
    cell *= 1.05f;
  }
  grid_cell_ = cell;
  grid_inv_cell_ = 1 / cell;
  const float half_diag2 = 0.75f * cell * cell;  // the cell's half diagonal, squared: a cell is one value
  grid_.assign(size_t(grid_n_[0]) * size_t(grid_n_[1]) * size_t(grid_n_[2]), 0);
  parallel_for(size_t(0), size_t(grid_n_[2]), [&](size_t z) {
    for (int y = 0; y < grid_n_[1]; ++y)
      for (int x = 0; x < grid_n_[0]; ++x) {
        const Vec3f c = grid_box_.lo + Vec3f(float(x) + 0.5f, float(y) + 0.5f, float(z) + 0.5f) * cell;
        grid_[(z * size_t(grid_n_[1]) + size_t(y)) * size_t(grid_n_[0]) + size_t(x)] = cut_irradiance(c, half_diag2);
      }
  });
}

size_t LightBvh::grid_cell(Vec3f p) const {
  if (grid_.empty() || !grid_box_.contains(p)) return SIZE_MAX;
  int i[3];
  for (int a = 0; a < 3; ++a) i[a] = std::clamp(int((p[a] - grid_box_.lo[a]) * grid_inv_cell_), 0, grid_n_[a] - 1);
  return (size_t(i[2]) * size_t(grid_n_[1]) + size_t(i[1])) * size_t(grid_n_[0]) + size_t(i[0]);
}

void LightBvh::weigh_visibility(const EmitterView& scene, std::span<const Light> lights,
                                const std::function<bool(const Ray&)>& occluded) {
  if (grid_.empty() || infinite_.empty()) return;
  grid_sky_.assign(grid_.size(), 1);
  const size_t nx = size_t(grid_n_[0]), ny = size_t(grid_n_[1]);
  parallel_for(size_t(0), grid_.size(), [&](size_t c) {
    if (!(grid_[c] > 0)) return;
    // Cells that the clamp to [kMinShare, 1 - kMinShare] decides whatever the rays say are left as they are.
    const float e_inf = infinite_irradiance_, e_b = grid_[c];
    if (e_inf <= kMinShare * (e_inf + e_b * kVisibilityFloor) ||
        e_inf * kVisibilityFloor >= (1 - kMinShare) * (e_inf * kVisibilityFloor + e_b))
      return;
    Pcg32 rng(0x5eed + c);
    const Vec3f lo = grid_box_.lo + Vec3f(float(c % nx), float(c / nx % ny), float(c / (nx * ny))) * grid_cell_;
    int seen[2] = {0, 0}, tried[2] = {0, 0};  // bounded, at infinity
    for (int k = 0; k < kVisibilityRays; ++k) {
      const Vec3f q = lo + Vec3f(rng.next_float(), rng.next_float(), rng.next_float()) * grid_cell_;
      float pmf;
      uint32_t part;
      const int l = sample_bounded(q, {0, 0, 0}, rng.next_float(), 1, &pmf, &part);
      LightSample s;
      if (l >= 0 && sample_light(scene, lights[size_t(l)], q, {rng.next_float(), rng.next_float()}, &s, part)) {
        ++tried[0];
        seen[0] += !occluded(Ray{q, s.wi, s.distance * (1 - 1e-3f)});
      }
      const uint32_t inf = infinite_[std::min(size_t(rng.next_float() * float(infinite_.size())), infinite_.size() - 1)];
      if (sample_light(scene, lights[inf], q, {rng.next_float(), rng.next_float()}, &s)) {
        ++tried[1];
        seen[1] += !occluded(Ray{q, s.wi, kInfinity});
      }
    }
    // Regularised: no ray says neither side is dark for certain (and points inside solids see nothing); a cell
    // that sees every ray it tried keeps its unweighed estimate.
    const auto fraction = [](int seen, int tried) {
      return std::max(kVisibilityFloor, (float(seen) + 0.25f) / (float(tried) + 0.25f));
    };
    grid_[c] *= fraction(seen[0], tried[0]);
    grid_sky_[c] = fraction(seen[1], tried[1]);
  });
}

uint32_t LightBvh::build(std::vector<Node>& nodes, std::vector<uint32_t>& ids, size_t begin, size_t end,
                         const std::vector<LightBounds>& all, const std::vector<Item>& items, uint64_t trail,
                         int depth) {
  const uint32_t index = uint32_t(nodes.size());
  nodes.emplace_back();
  if (end - begin == 1) {
    nodes[index] = {all[ids[begin]], items[ids[begin]].light, items[ids[begin]].part, true};
    trail_[ids[begin]] = trail;
    return index;
  }
  LightBounds node;
  Bounds3f centroids;
  for (size_t i = begin; i < end; ++i) node = merge(node, all[ids[i]]), centroids.extend(all[ids[i]].bounds.center());
  // Binned split minimising the surface-area-orientation heuristic (Conty Estevez and Kulla 2018) over the
  // three axes; equal centroids (or a depth near the trail's 64 bits) fall back to a split in the middle.
  size_t mid = begin + (end - begin) / 2;
  const Vec3f extent = centroids.diagonal();
  if (depth < 60 && std::max({extent.x, extent.y, extent.z}) > 0) {
    constexpr int kBins = 12;
    float best = kInfinity;
    int best_axis = -1, best_bin = 0;
    const float kr = std::max({extent.x, extent.y, extent.z});
    for (int axis = 0; axis < 3; ++axis) {
      if (extent[axis] <= 0) continue;
      LightBounds bins[kBins];
      const auto bin_of = [&](uint32_t id) {
        const float t = (all[id].bounds.center()[axis] - centroids.lo[axis]) / extent[axis];
        return std::min(int(t * kBins), kBins - 1);
      };
      for (size_t i = begin; i < end; ++i) bins[bin_of(ids[i])] = merge(bins[bin_of(ids[i])], all[ids[i]]);
      for (int split = 1; split < kBins; ++split) {
        LightBounds lo, hi;
        for (int k = 0; k < split; ++k) lo = merge(lo, bins[k]);
        for (int k = split; k < kBins; ++k) hi = merge(hi, bins[k]);
        if (lo.phi == 0 || hi.phi == 0) continue;
        const auto cost = [](const LightBounds& b) {
          return b.phi * orientation_measure(b.normals.cos_theta, b.cos_theta_e) * b.bounds.surface_area();
        };
        // Regularised by the axis' share of the extent, so thin slabs are not cut along their thin side.
        const float c = (cost(lo) + cost(hi)) * kr / extent[axis];
        if (c < best) best = c, best_axis = axis, best_bin = split;
      }
    }
    if (best_axis >= 0) {
      const int axis = best_axis;
      const auto it = std::partition(ids.begin() + long(begin), ids.begin() + long(end), [&](uint32_t id) {
        const float t = (all[id].bounds.center()[axis] - centroids.lo[axis]) / extent[axis];
        return std::min(int(t * kBins), kBins - 1) < best_bin;
      });
      mid = size_t(it - ids.begin());
      if (mid == begin || mid == end) mid = begin + (end - begin) / 2;
    }
  }
  if (depth >= 63) throw Error("light BVH: too deep (over 63 levels)");
  build(nodes, ids, begin, mid, all, items, trail, depth + 1);
  const uint32_t second = build(nodes, ids, mid, end, all, items, trail | (uint64_t(1) << depth), depth + 1);
  nodes[index] = {node, second, 0, false};
  return index;
}

int LightBvh::sample(Vec3f p, Vec3f n, float u, float* pmf, uint32_t* part) const {
  if (only_light_ >= 0) {
    *pmf = 1;
    *part = only_part_;
    return only_light_;
  }
  *pmf = 0;
  *part = 0;
  const bool has_bvh = !packed_.empty();
  const float p_inf = infinite_probability(p, n);
  if (u < p_inf) {
    const size_t k = std::min(size_t(u / p_inf * float(infinite_.size())), infinite_.size() - 1);
    *pmf = p_inf / float(infinite_.size());
    return int(infinite_[k]);
  }
  if (!has_bvh) return -1;
  u = std::min((u - p_inf) / (1 - p_inf), 0x1.fffffep-1f);
  return sample_bounded(p, n, u, 1 - p_inf, pmf, part);
}

void LightBvh::sample_batch(size_t count, const Vec3f* p, const Vec3f* n, const float* u, int* light, float* pmf,
                            uint32_t* part) const {
  // The receivers that descend, gathered as the kernel reads them; one buffer per thread, grown to the largest
  // shading queue and then reused, so no call allocates once a render is under way.
  struct Descents {
    std::vector<float> px, py, pz, nx, ny, nz, u, prob, pmf;
    std::vector<int32_t> light;
    std::vector<uint32_t> part, from;  // from: the receiver's index in the call
    void resize(size_t n) {
      for (auto* v : {&px, &py, &pz, &nx, &ny, &nz, &u, &prob, &pmf}) v->resize(n);
      light.resize(n);
      part.resize(n);
      from.resize(n);
    }
  };
  thread_local Descents d;
  // One light, or a root that is a leaf: sample() itself (no descent to share).
  const bool descend = !packed_.empty() && !packed_[0].leaf() && only_light_ < 0;
  if (descend) d.resize(count);
  size_t m = 0;
  for (size_t k = 0; k < count; ++k) {
    if (!descend) {
      light[k] = sample(p[k], n[k], u[k], &pmf[k], &part[k]);
      continue;
    }
    // sample()'s steps before the descent (every entry's results are written below or by sample()).
    const float p_inf = infinite_probability(p[k], n[k]);
    if (u[k] < p_inf) {
      light[k] = sample(p[k], n[k], u[k], &pmf[k], &part[k]);
      continue;
    }
    d.px[m] = p[k].x;
    d.py[m] = p[k].y;
    d.pz[m] = p[k].z;
    d.nx[m] = n[k].x;
    d.ny[m] = n[k].y;
    d.nz[m] = n[k].z;
    d.u[m] = std::min((u[k] - p_inf) / (1 - p_inf), 0x1.fffffep-1f);
    d.prob[m] = 1 - p_inf;
    d.from[m++] = uint32_t(k);
  }
  if (m == 0) return;
  const LightDescentInput in{d.px.data(), d.py.data(), d.pz.data(), d.nx.data(),
                             d.ny.data(), d.nz.data(), d.u.data(),  d.prob.data()};
  light_bvh_descend(packed_.data(), m, in, d.light.data(), d.pmf.data(), d.part.data());
  for (size_t j = 0; j < m; ++j) {
    light[d.from[j]] = d.light[j];
    pmf[d.from[j]] = d.pmf[j];
    part[d.from[j]] = d.part[j];
  }
}

int LightBvh::sample_bounded(Vec3f p, Vec3f n, float u, float prob, float* pmf, uint32_t* part) const {
  *pmf = 0;
  *part = 0;
  // A root that is a leaf is checked here; a child is only ever chosen with an importance above 0.
  if (packed_[0].leaf() && importance(packed_[0], p, n) <= 0) return -1;
  const PackedNode* nd = &packed_[0];
  while (!nd->leaf()) {
    const PackedNode* ch = &packed_[nd->index];
    const float i0 = importance(ch[0], p, n), i1 = importance(ch[1], p, n);
    if (i0 <= 0 && i1 <= 0) return -1;
    const float p0 = i0 / (i0 + i1);
    if (u < p0) {
      prob *= p0;
      u = std::min(u / p0, 0x1.fffffep-1f);
      nd = ch;
    } else {
      prob *= 1 - p0;
      u = std::min((u - p0) / (1 - p0), 0x1.fffffep-1f);
      nd = ch + 1;
    }
  }
  *pmf = prob;
  *part = nd->part();
  return int(nd->index);
}

float LightBvh::infinite_probability(Vec3f p, Vec3f n) const {
  if (infinite_.empty()) return 0;
  if (packed_.empty()) return 1;
  float bounded = 0, at_infinity = infinite_irradiance_;
  if (const size_t c = grid_cell(p); c != SIZE_MAX && grid_[c] > 0) {
    bounded = grid_[c];
    if (!grid_sky_.empty()) at_infinity *= grid_sky_[c];
  } else {
    // Outside the grid, or no light reaches the cell's centre (p may still see one): the root's importance is
    // its power over the squared distance (light_bounds), divided by pi an estimate of the irradiance there.
    bounded = importance(packed_[0], p, n) / kPi;
  }
  if (!(bounded > 0)) return 1;
  if (!(at_infinity > 0)) return 0.5f;
  return std::clamp(at_infinity / (at_infinity + bounded), kMinShare, 1 - kMinShare);
}

float LightBvh::pmf(Vec3f p, Vec3f n, int light, uint32_t part) const {
  if (light < 0 || size_t(light) >= light_count_ || in_bvh_[size_t(light)] == 0) return 0;
  if (only_light_ >= 0) return part == only_part_ ? 1.0f : 0.0f;  // in_bvh_ holds one light then
  const float p_inf = infinite_probability(p, n);
  if (in_bvh_[size_t(light)] == 2) return part == 0 ? p_inf / float(infinite_.size()) : 0.0f;
  if (part >= item_count_[size_t(light)]) return 0;
  float prob = 1 - p_inf;
  uint64_t trail = trail_[first_item_[size_t(light)] + part];
  const PackedNode* nd = &packed_[0];
  while (!nd->leaf()) {
    const PackedNode* ch = &packed_[nd->index];
    const float i0 = importance(ch[0], p, n), i1 = importance(ch[1], p, n);
    if (i0 <= 0 && i1 <= 0) return 0;
    const bool second = trail & 1;
    prob *= (second ? i1 : i0) / (i0 + i1);  // 0 when the light's side cannot reach p
    nd = ch + (second ? 1 : 0);
    trail >>= 1;
  }
  // A part of no power is in no leaf: its trail leads to another item's leaf.
  if (nd->index != uint32_t(light) || nd->part() != part) return 0;
  return nd != &packed_[0] || importance(*nd, p, n) > 0 ? prob : 0;
}

}  // namespace torte
