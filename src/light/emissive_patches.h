// Many small emitters gathered into one light (LightKind::Patches): the exposed faces of emitting voxels and
// the emitting shapes inside voxel cells, placed in world space when the scene is flattened. A per-object area
// light would need one light record per voxel; here one light holds them all.
//
// Patches are chosen with probability proportional to their power (area x average radiance x sides), so the
// density per unit area of a point on patch k is
//     pdf_area = average(L_k) * sides_k / W,    W = sum over patches of area * average(L) * sides,
// which depends only on the patch's radiance and sidedness: a ray that hits an emitting voxel gets its MIS
// density without knowing which patch it hit (see light_pdf).
#pragma once
#include <cstdint>
#include <vector>

#include "core/rgb.h"
#include "core/sampling.h"
#include "core/vec.h"

namespace torte {

// One planar emitter: the parallelogram p + s e1 + t e2 (s, t in [0, 1]) or the triangle (p, p + e1, p + e2).
// 68 bytes; patches are only read when sampled (never by traversal).
struct EmissivePatch {
  Vec3f p, e1, e2;
  Vec3f n;       // unit normal of the emitting side (either side when two_sided)
  Rgb radiance;  // emitted radiance (linear RGB)
  float area = 0;
  bool triangle = false;
  bool two_sided = false;
};
static_assert(sizeof(EmissivePatch) == 68);

struct PatchPoint {
  Vec3f q, n;        // the point and its emitting side's normal
  Rgb radiance;
  bool two_sided;
  float pdf_area;    // density per unit area of choosing q (patch choice included)
};

class EmissivePatches {
 public:
  void add_parallelogram(Vec3f p, Vec3f e1, Vec3f e2, Vec3f n, Rgb radiance, bool two_sided);
  void add_triangle(Vec3f p0, Vec3f p1, Vec3f p2, Rgb radiance, bool two_sided);
  // Builds the selection table; call once after the last add. Throws torte::Error when nothing emits.
  void finish();

  size_t size() const { return patches_.size(); }
  const EmissivePatch& patch(size_t k) const { return patches_[k]; }
  // Emitted power / pi (W above): light selection weighs lights by power.
  float weight() const { return float(total_weight_); }
  // Density per unit area of a point on a patch with this radiance and sidedness (see the top of the file).
  float pdf_area(const Rgb& radiance, bool two_sided) const {
    return total_weight_ > 0 ? float(radiance.average() * (two_sided ? 2.0 : 1.0) / total_weight_) : 0.0f;
  }
  PatchPoint sample(Vec2f u) const;

 private:
  std::vector<EmissivePatch> patches_;
  Distribution1D select_;
  double total_weight_ = 0;
};

}  // namespace torte
