#include "render/wavefront.h"

#include <cmath>

#include "core/rng.h"
#include "render/igi.h"
#include "render/material_resolve.h"
#include "render/shade.h"

namespace torte {

namespace {
// Thin-lens sample dimension: above every per-bounce and per-light dimension (kDimAllLightsBase + depth * 4096 +
// light stays below 2^29 for any uint16 depth), so it never collides with them.
constexpr uint32_t kDimLens = 1u << 30;
}  // namespace

void WavefrontRenderer::render(const std::vector<SampleRequest>& requests, Film& film,
                               RenderStats& stats) {
  // `direct` is the same pipeline, stopped after the first non-specular scattering event (it follows specular
  // chains: mirrors and glass show the lit scene); its light-sampling strategy is chosen in the settings.
  max_depth_ = settings_.max_depth;
  spread_ = camera_.spread_angle();
  generate_camera_rays(requests);
  stats.camera_rays += requests.size();
  while (!active_.empty()) {
    trace(stats);
    add_emission_and_queue(stats);
    shade();
    trace_shadows(stats);
    if (vpls_) gather_vpls(stats);  // IGI: indirect light from the VPLs (render/igi.h)
    compact();
  }
  for (size_t i = 0; i < paths_.size(); ++i) {
    const Rgb& L = paths_.radiance[i];
    ++stats.samples_done;
    if (!L.is_finite()) {
      ++stats.dropped_samples;
      continue;
    }
    film.add_sample(paths_.pixel[i], L, paths_.filter_weight[i]);
  }
}

void WavefrontRenderer::generate_camera_rays(const std::vector<SampleRequest>& requests) {
  const size_t n = requests.size();
  paths_.resize(n);
  active_.resize(n);
  const uint32_t width = uint32_t(settings_.width);
  for (size_t i = 0; i < n; ++i) {
    const SampleRequest& r = requests[i];
    const Filter::Sample fs = settings_.filter.sample(sampler_.get_2d(r.pixel, r.sample, kDimFilter));
    const Vec2f raster = filter_raster_position(int(r.pixel % width), int(r.pixel / width), fs.offset,
                                               settings_.width, settings_.height);
    const Ray ray = camera_.has_lens() ? camera_.generate_ray(raster, sampler_.get_2d(r.pixel, r.sample, kDimLens))
                                       : camera_.generate_ray(raster);
    paths_.pixel[i] = r.pixel;
    paths_.sample[i] = r.sample;
    paths_.filter_weight[i] = fs.weight;
    paths_.origin[i] = ray.o;
    paths_.dir[i] = ray.d;
    paths_.beta[i] = Rgb(1);
    paths_.radiance[i] = Rgb(0);
    paths_.bsdf_pdf[i] = 0;
    paths_.depth[i] = 0;
    paths_.flags[i] = 0;
    paths_.eta_scale[i] = 1;
    paths_.footprint[i] = camera_.footprint_at_origin();
    active_[i] = uint32_t(i);
  }
}

template <class RayOf>
RaySoA WavefrontRenderer::gather_rays(size_t count, RayOf&& ray_of) {
  for (auto& b : ray_buf_) b.resize(count);
  for (size_t k = 0; k < count; ++k) {
    const Ray r = ray_of(k);
    ray_buf_[0][k] = r.o.x;
    ray_buf_[1][k] = r.o.y;
    ray_buf_[2][k] = r.o.z;
    ray_buf_[3][k] = r.d.x;
    ray_buf_[4][k] = r.d.y;
    ray_buf_[5][k] = r.d.z;
    ray_buf_[6][k] = r.t_max;
  }
  return {ray_buf_[0].data(), ray_buf_[1].data(), ray_buf_[2].data(), ray_buf_[3].data(),
          ray_buf_[4].data(), ray_buf_[5].data(), ray_buf_[6].data()};
}

void WavefrontRenderer::trace(RenderStats& stats) {
  const size_t n = active_.size();
  if (n == 0) return;
  const RaySoA rays = gather_rays(n, [&](size_t k) {
    const uint32_t i = active_[k];
    return Ray{paths_.origin[i], paths_.dir[i], kInfinity};
  });
  hit_buf_.resize(n);
  // Camera rays of a tile come pixel by pixel, neighbours next to each other: trace them as packets. Bounced
  // rays are incoherent and go one at a time.
  const bool camera_rays = paths_.depth[active_[0]] == 0;
  scene_.intersect(rays, n, hit_buf_.data(), camera_rays);
  for (size_t k = 0; k < n; ++k) paths_.hit[active_[k]] = hit_buf_[k];
  // Camera rays were counted when generated; everything traced after the first segment is an extension ray.
  if (!camera_rays) stats.extension_rays += n;
}

void WavefrontRenderer::add_emission_and_queue(RenderStats&) {
  const Scene& scene = scene_;
  const bool all_lights = settings_.sample_all_lights;
  const bool direct = ends_after_first_scatter(settings_.integrator);  // direct and igi
  // MIS weight of emission found by BSDF sampling against the light-sampling strategy that could have found it.
  auto emission_weight = [&](uint32_t i, int light_index, float light_pdf) {
    // Seen by the camera or through a delta lobe: no light sampling competes.
    if (paths_.depth[i] == 0 || (paths_.flags[i] & kPathSpecular)) return 1.0f;
    const float pmf = all_lights ? 1.0f : scene.light_selection.pmf(light_index);
    return power_heuristic(1, paths_.bsdf_pdf[i], 1, pmf * light_pdf);
  };

  uint32_t counts[kMaterialTypeCount] = {};
  size_t kept = 0;
  for (const uint32_t i : active_) {
    const Hit& hit = paths_.hit[i];
    const Vec3f d = paths_.dir[i];
    if (hit.prim == kNoHit) {
      for (size_t l = 0; l < scene.lights.size(); ++l) {
        const Light& light = scene.lights[l];
        if (!is_infinite_light(light)) continue;
        const Rgb le = escaped_radiance(light, d);
        if (le.is_black()) continue;
        const float w = emission_weight(i, int(l), light_pdf(scene, light, paths_.origin[i], d, nullptr, kInfinity));
        paths_.radiance[i] += paths_.beta[i] * le * w;
      }
      paths_.depth[i] = kPathEnded;
      continue;
    }
    const Ray ray{paths_.origin[i], d, hit.t};
    const SurfaceHit s = scene.surface(ray, hit);
    const SceneObject& object = scene.objects[s.object];
    if (object.area_light >= 0) {
      const Light& light = scene.lights[size_t(object.area_light)];
      const Rgb le = area_emission(light, s, d);
      if (!le.is_black()) {
        const float w = emission_weight(i, object.area_light, light_pdf(scene, light, paths_.origin[i], d, &s, hit.t));
        paths_.radiance[i] += paths_.beta[i] * le * w;
      }
    } else if (const SurfaceEmission* e = patch_emission(scene, s); e && (e->two_sided || dot(s.ng, d) < 0)) {
      // An emitting voxel face or cell shape (a Patches light).
      const Light& light = scene.lights[size_t(e->light)];
      const float w = emission_weight(i, e->light, light_pdf(scene, light, paths_.origin[i], d, &s, hit.t));
      paths_.radiance[i] += paths_.beta[i] * e->radiance * w;
    }
    const bool direct_done = direct && (paths_.flags[i] & kPathScattered);
    if (paths_.depth[i] >= max_depth_ || direct_done) {
      paths_.depth[i] = kPathEnded;
      continue;
    }
    paths_.surface[i] = s;
    paths_.footprint[i] += spread_ * hit.t;  // ray-cone width at the hit
    const uint32_t px = paths_.pixel[i], si = paths_.sample[i];
    // Voxel faces and cell shapes carry their own material (SurfaceHit::material, -1 = the object's).
    const MaterialRef base = scene.material_of(s);
    const MaterialRef m = resolve_material(
        scene, base, paths_.surface[i], paths_.footprint[i],
        [&] { return sampler_.get_1d(px, si, bounce_dim(paths_.depth[i], kDimMaterialMix)); },
        mix_bits((uint64_t(px) << 32 | si) ^ (uint64_t(paths_.depth[i]) << 56)));
    paths_.material[i] = m;
    ++counts[int(m.type)];
    active_[kept++] = i;
  }
  active_.resize(kept);

  // Counting sort of the surviving hits by material type: one contiguous queue per type.
  queue_begin_[0] = 0;
  for (int t = 0; t < kMaterialTypeCount; ++t) queue_begin_[t + 1] = queue_begin_[t] + counts[t];
  uint32_t cursor[kMaterialTypeCount];
  for (int t = 0; t < kMaterialTypeCount; ++t) cursor[t] = queue_begin_[t];
  material_queue_.resize(kept);
  for (const uint32_t i : active_)
    material_queue_[cursor[int(paths_.material[i].type)]++] = i;
}

void WavefrontRenderer::shade() {
  shadows_.clear();
  vpl_hits_.clear();
  const ShadeContext ctx{scene_, settings_, sampler_, paths_, shadows_, vpls_ ? &vpl_hits_ : nullptr};
  auto queue = [&](MaterialType t) {
    return std::span<const uint32_t>(material_queue_.data() + queue_begin_[int(t)],
                                     queue_begin_[int(t) + 1] - queue_begin_[int(t)]);
  };
  // One kernel per shaded material type, each over its contiguous queue.
  for_each_shaded_type([&](auto t) {
    shade_queue<t()>(ctx, queue(t()), std::get<int(t())>(scratch_));
    vpl_hits_end_[int(t())] = vpl_hits_.size();
  });
}

void WavefrontRenderer::gather_vpls(RenderStats& stats) {
  shadows_.clear();
  auto flush = [&] {
    trace_shadows(stats, true);  // runs of rays from one tile towards one VPL: packets
    shadows_.clear();
  };
  auto hits = [&](size_t t) {
    const size_t begin = t == 0 ? 0 : vpl_hits_end_[t - 1];
    return std::span<const VplHit>(vpl_hits_.data() + begin, vpl_hits_end_[t] - begin);
  };
  for_each_shaded_type([&](auto t) {
    torte::gather_vpls<t()>(*vpls_, std::get<int(t())>(scratch_), hits(int(t())), paths_, settings_.seed, shadows_,
                            vpl_order_, flush);
  });
  flush();
}

void WavefrontRenderer::trace_shadows(RenderStats& stats, bool coherent) {
  const size_t n = shadows_.size();
  if (n == 0) return;
  const RaySoA rays = gather_rays(n, [&](size_t k) {
    return Ray{shadows_.origin[k], shadows_.dir[k], shadows_.t_max[k]};
  });
  occluded_buf_.resize(n);
  scene_.occluded(rays, n, occluded_buf_.data(), coherent);
  for (size_t k = 0; k < n; ++k)
    if (!occluded_buf_[k]) paths_.radiance[shadows_.path[k]] += shadows_.contribution[k];
  stats.shadow_rays += n;
}

void WavefrontRenderer::compact() {
  size_t kept = 0;
  for (const uint32_t i : active_)
    if (paths_.depth[i] != kPathEnded) active_[kept++] = i;
  active_.resize(kept);
}

}  // namespace torte
