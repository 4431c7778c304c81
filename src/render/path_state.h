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
  std::vector<Vec3f> prev_p;         // the vertex that ray left (the light BVH's pmf there, for MIS)
  std::vector<Vec3f> prev_n;         // ... and its geometric normal (the light BVH weighs the receiver's cosine)
  std::vector<uint16_t> depth;       // scattering events so far
  std::vector<uint8_t> flags;        // PathFlags
  std::vector<float> eta_scale;      // product of eta^2 over refractions (Russian roulette ignores it)
  std::vector<float> footprint;      // ray-cone width at the ray's origin (texture filtering)

  void resize(size_t n) {
    pixel.resize(n); sample.resize(n); filter_weight.resize(n); beta.resize(n); radiance.resize(n);
    bsdf_pdf.resize(n); prev_p.resize(n); prev_n.resize(n); depth.resize(n); flags.resize(n); eta_scale.resize(n); footprint.resize(n);
  }
  size_t size() const { return pixel.size(); }
};

/// Rays in SoA form, in queue order, each with the path it belongs to. The arrays only grow (size() counts the
/// rays in use), so a push is one capacity check for all eight arrays, not eight push_backs.
struct RayQueue {
  std::vector<float> ox, oy, oz, dx, dy, dz, t_max;
  std::vector<uint32_t> path;

  void clear() { count_ = 0; }
  /// Makes room for `n` rays in all, so that pushes up to there do not reallocate.
  void reserve(size_t n) {
    if (n > path.size()) grow(n);
  }
  void push(Vec3f o, Vec3f d, float t, uint32_t p) {
    if (count_ == path.size()) grow(count_ * 2 + 256);
    const size_t k = count_++;
    ox[k] = o.x; oy[k] = o.y; oz[k] = o.z;
    dx[k] = d.x; dy[k] = d.y; dz[k] = d.z;
    t_max[k] = t; path[k] = p;
  }
  size_t size() const { return count_; }
  Vec3f origin(size_t k) const { return {ox[k], oy[k], oz[k]}; }
  Vec3f dir(size_t k) const { return {dx[k], dy[k], dz[k]}; }
  RaySoA soa() const { return {ox.data(), oy.data(), oz.data(), dx.data(), dy.data(), dz.data(), t_max.data()}; }

 private:
  void grow(size_t n) {
    for (auto* v : {&ox, &oy, &oz, &dx, &dy, &dz, &t_max}) v->resize(n);
    path.resize(n);
  }
  size_t count_ = 0;
};

/// Shadow rays and the radiance each carries to its path if unoccluded.
struct ShadowQueue : RayQueue {
  std::vector<Rgb> contribution;
  void push(Vec3f o, Vec3f d, float t, Rgb c, uint32_t p) {
    const size_t k = size();
    RayQueue::push(o, d, t, p);
    if (contribution.size() < path.size()) contribution.resize(path.size());  // follows the rays' growth
    contribution[k] = c;
  }
};

/// Trace results of a RayQueue, by queue slot: the hit, and for hits queued for shading the reconstructed
/// surface and the resolved (leaf) material. The arrays only grow: shrinking and regrowing them every batch would
/// value-initialise every SurfaceHit again.
struct HitQueue {
  std::vector<Hit> hit;
  std::vector<SurfaceHit> surface;
  std::vector<MaterialRef> material;
  /// Makes room for slots [0, n).
  void resize(size_t n) {
    if (hit.size() >= n) return;
    hit.resize(n);
    surface.resize(n);
    material.resize(n);
  }
};

}  // namespace torte
