// The state of a wavefront, structure of arrays. Rays live in RayQueue in exactly the layout the trace call
// takes (Scene::intersect / occluded over RaySoA), written in compacted order by camera-ray generation and by
// path continuation, so no stage gathers rays into temporary arrays or copies hits back. Per-path state
// (PathState) is indexed by path; per-ray state (the queue, its hits, surfaces and materials) by queue slot.
#pragma once
#include <cstdint>
#include <vector>

#include "core/rgb.h"
#include "core/vec.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace torte {

// PathState::flags bits.
enum PathFlags : uint8_t {
  kPathSpecular = 1,   // the current ray left a delta lobe: emission it finds gets MIS weight 1
  kPathScattered = 2,  // the current ray left a non-specular event
};

/// Per-path state, indexed by path (the position of the camera sample in its batch).
struct PathState {
  std::vector<uint32_t> pixel;       // linear pixel index in the image
  std::vector<uint32_t> sample;      // sample index within the pixel
  std::vector<float> filter_weight;  // f/pdf of the filter sample
  std::vector<Rgb> beta;             // throughput
  std::vector<Rgb> radiance;         // accumulated estimate
  std::vector<float> bsdf_pdf;       // pdf of the BSDF sample that produced the current ray (for MIS)
  std::vector<uint16_t> depth;       // scattering events so far
  std::vector<uint8_t> flags;        // PathFlags
  std::vector<float> eta_scale;      // product of eta^2 over refractions (Russian roulette ignores it)
  std::vector<float> footprint;      // ray-cone width at the ray's origin (texture filtering)

  void resize(size_t n) {
    pixel.resize(n); sample.resize(n); filter_weight.resize(n); beta.resize(n); radiance.resize(n);
    bsdf_pdf.resize(n); depth.resize(n); flags.resize(n); eta_scale.resize(n); footprint.resize(n);
  }
  size_t size() const { return pixel.size(); }
};

/// Rays in SoA form, in queue order, each with the path it belongs to.
struct RayQueue {
  std::vector<float> ox, oy, oz, dx, dy, dz, t_max;
  std::vector<uint32_t> path;

  void clear() {
    ox.clear(); oy.clear(); oz.clear(); dx.clear(); dy.clear(); dz.clear(); t_max.clear(); path.clear();
  }
  void push(Vec3f o, Vec3f d, float t, uint32_t p) {
    ox.push_back(o.x); oy.push_back(o.y); oz.push_back(o.z);
    dx.push_back(d.x); dy.push_back(d.y); dz.push_back(d.z);
    t_max.push_back(t); path.push_back(p);
  }
  size_t size() const { return path.size(); }
  Vec3f origin(size_t k) const { return {ox[k], oy[k], oz[k]}; }
  Vec3f dir(size_t k) const { return {dx[k], dy[k], dz[k]}; }
  RaySoA soa() const { return {ox.data(), oy.data(), oz.data(), dx.data(), dy.data(), dz.data(), t_max.data()}; }
};

/// Shadow rays and the radiance each carries to its path if unoccluded.
struct ShadowQueue : RayQueue {
  std::vector<Rgb> contribution;
  void clear() {
    RayQueue::clear();
    contribution.clear();
  }
  void push(Vec3f o, Vec3f d, float t, Rgb c, uint32_t p) {
    RayQueue::push(o, d, t, p);
    contribution.push_back(c);
  }
};

/// Trace results of a RayQueue, by queue slot: the hit, and for hits queued for shading the reconstructed
/// surface and the resolved (leaf) material.
struct HitQueue {
  std::vector<Hit> hit;
  std::vector<SurfaceHit> surface;
  std::vector<MaterialRef> material;
  void resize(size_t n) {
    hit.resize(n);
    surface.resize(n);
    material.resize(n);
  }
};

}  // namespace torte
