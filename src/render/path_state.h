// Per-path state of a wavefront, stored as structure of arrays: each stage touches only the fields it needs.
#pragma once
#include <cstdint>
#include <vector>

#include "core/rgb.h"
#include "core/vec.h"
#include "scene/scene.h"

namespace torte {

constexpr uint16_t kPathEnded = 0xffff;

// PathState::flags bits.
enum PathFlags : uint8_t {
  kPathSpecular = 1,     // the current ray left a delta lobe: emission it finds gets MIS weight 1
  kPathScattered = 2,    // a non-specular event happened (the `direct` integrator ends at the next hit)
};

struct PathState {
  std::vector<uint32_t> pixel;        // linear pixel index in the image
  std::vector<uint32_t> sample;       // sample index within the pixel
  std::vector<float> filter_weight;   // f/pdf of the filter sample
  std::vector<Vec3f> origin, dir;     // the path's current ray
  std::vector<Rgb> beta;              // throughput
  std::vector<Rgb> radiance;          // accumulated estimate
  std::vector<float> bsdf_pdf;        // pdf of the BSDF sample that produced the current ray (for MIS)
  std::vector<uint16_t> depth;        // scattering events so far; kPathEnded once the path ends
  std::vector<uint8_t> flags;         // PathFlags
  std::vector<float> eta_scale;       // product of eta^2 over refractions (Russian roulette ignores it)
  std::vector<float> footprint;       // ray-cone width at the ray's origin (texture filtering)
  std::vector<MaterialRef> material;  // resolved (leaf) material of the current hit
  std::vector<Hit> hit;               // trace result for the current ray
  std::vector<SurfaceHit> surface;    // reconstructed hit surface (valid for paths queued for shading)

  void resize(size_t n) {
    pixel.resize(n); sample.resize(n); filter_weight.resize(n); origin.resize(n); dir.resize(n);
    beta.resize(n); radiance.resize(n); bsdf_pdf.resize(n); depth.resize(n); flags.resize(n); eta_scale.resize(n);
    footprint.resize(n); material.resize(n); hit.resize(n); surface.resize(n);
  }
  size_t size() const { return pixel.size(); }
};

// A shadow ray and the radiance it carries if unoccluded (SoA).
struct ShadowQueue {
  std::vector<Vec3f> origin, dir;
  std::vector<float> t_max;
  std::vector<Rgb> contribution;
  std::vector<uint32_t> path;
  void clear() { origin.clear(); dir.clear(); t_max.clear(); contribution.clear(); path.clear(); }
  void push(Vec3f o, Vec3f d, float t, Rgb c, uint32_t p) {
    origin.push_back(o); dir.push_back(d); t_max.push_back(t); contribution.push_back(c); path.push_back(p);
  }
  size_t size() const { return path.size(); }
};

}  // namespace torte
