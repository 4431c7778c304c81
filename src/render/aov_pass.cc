#include "render/aov_pass.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/parallel.h"
#include "core/ray.h"
#include "core/rng.h"
#include "material/material_traits.h"
#include "render/material_resolve.h"

namespace torte {

namespace {

constexpr struct {
  Aov aov;
  const char* name;
} kAovNames[] = {{Aov::Albedo, "albedo"},
                 {Aov::Normal, "normal"},
                 {Aov::Depth, "depth"},
                 {Aov::Position, "position"},
                 {Aov::MaterialId, "material_id"},
                 {Aov::Emission, "emission"},
                 {Aov::Samples, "samples"},
                 {Aov::Variance, "variance"},
                 {Aov::TraversalCost, "traversal_cost"},
                 {Aov::Glossiness, "glossiness"}};

// Mirrors and glass are followed this many bounces for the albedo and normal of what they show.
constexpr int kMaxSpecularBounces = 8;
// Pixels whose samples disagree take this many times their samples again (render_aovs: 16 become 16 + 64, a grid
// twice as fine), and normals disagree when their mean is shorter than this (about 18 degrees of spread).
constexpr int kEdgeRefine = 4;
constexpr float kEdgeNormalAgreement = 0.95f;
// BSDF samples averaged for the albedo at the surface that defines it (no rays traced for them): a glossy or
// layered BSDF's sample weights vary, and one per camera sample left its albedo noisy.
constexpr int kAlbedoSamples = 4;

// 1 + a dense index of `m` over the scene's material tables (shaded types in enum order, then mixes, bumps).
float material_id(const MaterialTables& tables, MaterialRef m) {
  uint32_t offset = 0, id = 0;
  bool found = false;
  for_each_shaded_type([&](auto tag) {
    constexpr MaterialType T = decltype(tag)::value;
    if (m.type == T) id = offset + m.index, found = true;
    offset += uint32_t(MaterialTraits<T>::params(tables).size());
  });
  if (!found && m.type == MaterialType::Mix) id = offset + m.index, found = true;
  offset += uint32_t(tables.mix.size());
  if (!found) id = offset + m.index;
  return float(id + 1);
}

Rgb clamp01(Rgb c) { return {std::clamp(c.r, 0.0f, 1.0f), std::clamp(c.g, 0.0f, 1.0f), std::clamp(c.b, 0.0f, 1.0f)}; }

Rgb sky(const Scene& scene, Vec3f d) {
  Rgb L;
  for (const uint32_t l : scene.infinite_lights) L += escaped_radiance(scene.lights[l], d);
  return clamp01(L);
}

// What one camera sample contributes to the AOVs.
struct AovSample {
  bool hit = false;
  Rgb albedo, emitted;
  Vec3f normal{0, 0, 0}, position{0, 0, 0};
  float depth = kInfinity;
  float material = 0;
  float gloss = 0;
};

// Radiance emitted towards -d at the hit: an area light's, or an emitting voxel face's or cell shape's (as
// stage_emission.h finds them), so that a voxel world's torches and lava are in the layer too.
Rgb emitted_at(const Scene& scene, const SurfaceHit& s, Vec3f d) {
  if (const int area = scene.objects[s.object].area_light; area >= 0)
    return area_emission(scene, scene.lights[size_t(area)], s, d);
  if (const SurfaceEmission* e = patch_emission_towards(scene, s, d)) return e->radiance;
  return Rgb(0);
}

// Follows the camera ray `ray` (already intersected: `hit`) through specular bounces to the first surface with a
// non-specular lobe; its BSDF sample weight f |cos| / pdf is an unbiased estimate of its directional albedo.
AovSample trace_sample(const Scene& scene, Ray ray, Hit hit, bool was_hit, Vec3f forward, Pcg32& rng,
                       TraversalCost* cost) {
  AovSample out;
  Rgb beta(1);
  for (int bounce = 0; bounce <= kMaxSpecularBounces; ++bounce) {
    if (!was_hit) {
      out.albedo += beta * sky(scene, ray.d);
      return out;
    }
    SurfaceHit s = scene.surface(Ray{ray.o, ray.d, hit.t}, hit);
    const MaterialRef assigned = scene.material_of(s);
    if (bounce == 0) {
      out.hit = true;
      out.position = s.p;
      out.depth = hit.t * dot(ray.d, forward);
      out.material = material_id(scene.materials, assigned);
      out.emitted = emitted_at(scene, s, ray.d);
    }
    const MaterialRef m = resolve_material(scene, assigned, s, 0.0f, [&rng] { return rng.next_float(); },
                                           rng.next_u32());
    const Frame frame = Frame::from_z(s.ns);
    const Vec3f wo = -ray.d, wo_local = frame.to_local(wo);
    const TextureContext tc = texture_context(s, 0.0f);
    BsdfSample bs;
    bool sampled = false, non_specular = false;
    float gloss = 0;
    Rgb albedo;  // at a non-specular surface: the mean weight of kAlbedoSamples BSDF samples
    const float uc = rng.next_float();
    const Vec2f u{rng.next_float(), rng.next_float()};
    dispatch_shaded(m.type, [&](auto tag) {
      constexpr MaterialType T = decltype(tag)::value;
      const auto bsdf = MaterialTraits<T>::bsdf(scene.materials, scene.textures, m.index, tc, TransportMode::Radiance);
      non_specular = bsdf.has_non_specular();
      sampled = bsdf.sample(wo_local, uc, u, &bs) && bs.pdf > 0;
      if (!non_specular) return;
      gloss = kPi * bsdf.pdf(wo_local, Vec3f(-wo_local.x, -wo_local.y, wo_local.z));
      if (sampled) albedo = bs.weight();
      for (int j = 1; j < kAlbedoSamples; ++j) {
        BsdfSample more;
        const float uc2 = rng.next_float();
        const Vec2f u2{rng.next_float(), rng.next_float()};
        if (bsdf.sample(wo_local, uc2, u2, &more) && more.pdf > 0) albedo += more.weight();
      }
      albedo = albedo / float(kAlbedoSamples);
    });
    if (non_specular || !sampled || bounce == kMaxSpecularBounces) {
      // The first surface that is not a perfect mirror or glass defines albedo and normal.
      out.normal = dot(s.ns, wo) < 0 ? -s.ns : s.ns;
      out.gloss = std::isfinite(gloss) ? gloss : 0.0f;
      // (A delta lobe picked from a BSDF that also has others counts with its specular weight.)
      if (non_specular) out.albedo += beta * albedo;
      else if (sampled) out.albedo += beta * bs.weight();
      return out;
    }
    beta *= bs.weight();
    if (beta.is_black()) return out;
    const Vec3f wi = frame.to_world(bs.wi);
    ray = Ray{offset_origin(s.p, s.ng, wi), wi, kInfinity};
    hit = Hit{};
    was_hit = scene.intersect(ray, &hit, cost);
  }
  return out;
}

// Emitted radiance over the footprint of a pixel on an emitter's edge, from kEdgeGrid^2 stratified camera rays:
// the denoiser rebuilds such pixels from it (film/denoise.h), and a coverage error there is multiplied by the
// emitter's radiance. Only edge pixels pay for it (few: an emitter's outline).
constexpr int kEdgeGrid = 32;
Rgb emitter_edge(const Scene& scene, const Camera& camera, const Filter& filter, int x, int y, Pcg32& rng) {
  double sum[3] = {}, wsum = 0;
  for (int k = 0; k < kEdgeGrid * kEdgeGrid; ++k) {
    const float cx = float(k % kEdgeGrid), cy = float(k / kEdgeGrid);
    const Filter::Sample fs = filter.sample({(cx + rng.next_float()) / kEdgeGrid, (cy + rng.next_float()) / kEdgeGrid});
    const Vec2f lens{rng.next_float(), rng.next_float()};
    Ray ray = camera.generate_ray({float(x) + 0.5f + fs.offset.x, float(y) + 0.5f + fs.offset.y}, lens);
    const Ray traced_from = ray;
    Hit hit;
    wsum += fs.weight;
    if (!scene.intersect(ray, &hit)) continue;
    const SurfaceHit s = scene.surface(Ray{traced_from.o, traced_from.d, hit.t}, hit);
    const Rgb le = emitted_at(scene, s, traced_from.d);
    sum[0] += fs.weight * le.r, sum[1] += fs.weight * le.g, sum[2] += fs.weight * le.b;
  }
  return wsum != 0 ? Rgb(float(sum[0] / wsum), float(sum[1] / wsum), float(sum[2] / wsum)) : Rgb(0);
}

}  // namespace

bool parse_aov(std::string_view name, Aov& out) {
  for (const auto& a : kAovNames)
    if (name == a.name) return out = a.aov, true;
  return false;
}

const char* aov_name(Aov aov) {
  for (const auto& a : kAovNames)
    if (a.aov == aov) return a.name;
  return "?";
}

ImageLayer samples_layer(int width, int height, const std::vector<uint32_t>& pixel_spp, int spp) {
  ImageLayer l{"samples", {"X"}, std::vector<float>(size_t(width) * size_t(height), float(spp))};
  if (pixel_spp.size() == l.values.size()) std::copy(pixel_spp.begin(), pixel_spp.end(), l.values.begin());
  return l;
}

std::vector<ImageLayer> render_aovs(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                                    const std::vector<Aov>& aovs, int samples, const std::atomic<bool>* cancel) {
  const int w = settings.width, h = settings.height;
  const size_t n = size_t(w) * size_t(h);
  // Per pixel, the finished values of every AOV (a few floats a pixel; only the requested ones are returned).
  const bool count = std::find(aovs.begin(), aovs.end(), Aov::TraversalCost) != aovs.end();
  struct Sums {
    std::vector<float> albedo, normal, position, depth, material, emitted, cost, gloss;
  } acc{std::vector<float>(3 * n), std::vector<float>(3 * n), std::vector<float>(3 * n), std::vector<float>(n),
        std::vector<float>(n),     std::vector<float>(3 * n), std::vector<float>(count ? 2 * n : 0),
        std::vector<float>(n)};
  const Vec3f forward = normalize(camera.desc().camera_to_world.apply_vector({0, 0, 1}));
  // How the pixel's samples saw area lights: a pixel all of whose few samples hit (or missed) an emitter may
  // still lie on its edge, which a neighbour that saw otherwise betrays (refined after the first pass).
  enum : uint8_t { kNone, kPartial, kFull };
  std::vector<uint8_t> coverage(n);
  parallel_for(0, h, [&](int y) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    std::map<float, int> ids;
    for (int x = 0; x < w; ++x) {
      const size_t pixel = size_t(y) * size_t(w) + size_t(x);
      Pcg32 rng(mix_bits(settings.seed * 0x9e3779b97f4a7c15ULL + pixel), 0xa0f5);
      double wsum = 0, whit = 0, al[3] = {}, nr[3] = {}, ps[3] = {}, em[3] = {}, dp = 0, cost[2] = {}, gl = 0;
      ids.clear();
      int taken_all = 0, emitting = 0, hits = 0, normals = 0;
      Vec3f normal_sum{0, 0, 0};  // unweighted, for the spread of the pixel's normals
      // `taken` samples over the pixel: the first m^2 stratified (an m x m grid, jittered, m = floor(sqrt(taken))),
      // so an edge's coverage, which the denoiser takes from the emission layer, converges faster than with
      // independent samples; the rest uniform (a grid of ceil(sqrt) cells, as before, left its last rows unsampled
      // when `taken` was not a square: 8 samples never looked at the pixel's bottom third).
      const auto take = [&](int taken) {
        taken_all += taken;
        int m = int(std::sqrt(float(taken)));
        while ((m + 1) * (m + 1) <= taken) ++m;
        while (m * m > taken) --m;
        for (int k = 0; k < taken; ++k) {
          const bool grid = k < m * m;
          const float cx = grid ? float(k % m) : 0.0f, cy = grid ? float(k / m) : 0.0f, cell = grid ? float(m) : 1.0f;
          const Filter::Sample fs = settings.filter.sample({(cx + rng.next_float()) / cell,
                                                            (cy + rng.next_float()) / cell});
          const Vec2f lens{rng.next_float(), rng.next_float()};
          Ray ray = camera.generate_ray({float(x) + 0.5f + fs.offset.x, float(y) + 0.5f + fs.offset.y}, lens);
          Hit hit;
          Ray traced = ray;  // intersect shortens t_max
          TraversalCost c;
          const bool was_hit = scene.intersect(traced, &hit, count ? &c : nullptr);
          const AovSample a = trace_sample(scene, ray, hit, was_hit, forward, rng, count ? &c : nullptr);
          // Counts are per sample, not filter-weighted: a negative filter lobe would make them negative.
          cost[0] += c.nodes, cost[1] += c.prims;
          const double wt = fs.weight;
          wsum += wt;
          al[0] += wt * a.albedo.r, al[1] += wt * a.albedo.g, al[2] += wt * a.albedo.b;
          nr[0] += wt * a.normal.x, nr[1] += wt * a.normal.y, nr[2] += wt * a.normal.z;
          em[0] += wt * a.emitted.r, em[1] += wt * a.emitted.g, em[2] += wt * a.emitted.b;
          gl += wt * a.gloss;
          emitting += !a.emitted.is_black();
          if (a.hit) {
            whit += wt;
            ps[0] += wt * a.position.x, ps[1] += wt * a.position.y, ps[2] += wt * a.position.z;
            dp += wt * a.depth;
            ++hits;
          }
          if (length_squared(a.normal) > 0) ++normals, normal_sum += a.normal;
          ++ids[a.material];
        }
      };
      take(samples);
      // A pixel whose samples disagree (an object's outline, a crease, a texture seam between materials) holds a
      // blend of features that its few samples estimate poorly, and the denoiser then finds no neighbour like
      // it: such pixels take kEdgeRefine times as many samples again.
      const bool mixed = ids.size() > 1 || (hits > 0 && hits < samples) ||
                         length(normal_sum) < kEdgeNormalAgreement * float(normals);
      if (mixed && samples > 1) take(kEdgeRefine * samples);
      const bool partial = emitting > 0 && emitting < taken_all;
      coverage[pixel] = partial ? kPartial : emitting > 0 ? kFull : kNone;
      const Rgb edge = partial ? emitter_edge(scene, camera, settings.filter, x, y, rng) : Rgb(-1);
      for (int c = 0; c < 3; ++c) {
        acc.albedo[3 * pixel + c] = wsum != 0 ? float(al[c] / wsum) : 0.0f;
        acc.emitted[3 * pixel + c] = edge.r >= 0 ? (&edge.r)[c] : wsum != 0 ? float(em[c] / wsum) : 0.0f;
        acc.position[3 * pixel + c] = whit != 0 ? float(ps[c] / whit) : 0.0f;
      }
      Vec3f normal{float(nr[0]), float(nr[1]), float(nr[2])};
      normal = length_squared(normal) > 0 ? normalize(normal) : normal;
      acc.normal[3 * pixel] = normal.x, acc.normal[3 * pixel + 1] = normal.y, acc.normal[3 * pixel + 2] = normal.z;
      acc.depth[pixel] = whit != 0 ? float(dp / whit) : kInfinity;
      acc.gloss[pixel] = wsum != 0 ? std::max(0.0f, float(gl / wsum)) : 0.0f;
      if (count)
        for (int c = 0; c < 2; ++c) acc.cost[2 * pixel + c] = float(cost[c] / taken_all);
      int best = -1;
      for (const auto& [id, count] : ids)  // ascending ids: ties go to the smaller
        if (count > best) best = count, acc.material[pixel] = id;
    }
  });
  parallel_for(0, h, [&](int y) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    for (int x = 0; x < w; ++x) {
      const size_t pixel = size_t(y) * size_t(w) + size_t(x);
      if (coverage[pixel] == kPartial) continue;
      bool edge = false;
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k)
        if (nx[k] >= 0 && ny[k] >= 0 && nx[k] < w && ny[k] < h) {
          const uint8_t other = coverage[size_t(ny[k]) * size_t(w) + size_t(nx[k])];
          edge |= other != coverage[pixel];
        }
      if (!edge) continue;
      Pcg32 rng(mix_bits(settings.seed * 0x9e3779b97f4a7c15ULL + pixel), 0xe06e);
      const Rgb e = emitter_edge(scene, camera, settings.filter, x, y, rng);
      acc.emitted[3 * pixel] = e.r, acc.emitted[3 * pixel + 1] = e.g, acc.emitted[3 * pixel + 2] = e.b;
    }
  });
  std::vector<ImageLayer> layers;
  std::vector<Aov> done;
  for (Aov aov : aovs) {
    if (std::find(done.begin(), done.end(), aov) != done.end()) continue;
    done.push_back(aov);
    switch (aov) {
      case Aov::Albedo: layers.push_back({"albedo", {"R", "G", "B"}, std::move(acc.albedo)}); break;
      case Aov::Normal: layers.push_back({"normal", {"X", "Y", "Z"}, std::move(acc.normal)}); break;
      case Aov::Position: layers.push_back({"position", {"X", "Y", "Z"}, std::move(acc.position)}); break;
      case Aov::Depth: layers.push_back({"depth", {"Z"}, std::move(acc.depth)}); break;
      case Aov::MaterialId: layers.push_back({"material_id", {"X"}, std::move(acc.material)}); break;
      case Aov::Emission: layers.push_back({"emission", {"R", "G", "B"}, std::move(acc.emitted)}); break;
      case Aov::TraversalCost: layers.push_back({"traversal_cost", {"nodes", "prims"}, std::move(acc.cost)}); break;
      case Aov::Glossiness: layers.push_back({"glossiness", {"Y"}, std::move(acc.gloss)}); break;
      case Aov::Samples: break;   // counted by the render itself (samples_layer)
      case Aov::Variance: break;  // the render's film keeps it (RenderOutput::variance)
    }
  }
  return layers;
}

}  // namespace torte
