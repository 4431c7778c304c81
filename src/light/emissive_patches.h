// Many small emitters gathered into one light (LightKind::Patches): the exposed faces of emitting voxels and
// the emitting shapes inside voxel cells, placed in world space when the scene is flattened. A per-object area
// light would need one light record per voxel; here one light holds them all.
//
// Two ways to sample them:
// - the whole light (selection by power, the bidirectional integrators, sample_all_lights): patches are chosen
//   with probability proportional to their power (area x average radiance x sides), so the density per unit
//   area of a point on patch k is
//       pdf_area = average(L_k) * sides_k / W,    W = sum over patches of area * average(L) * sides,
//   which depends only on the patch's radiance and sidedness (see light_pdf);
// - one part at a time (the light BVH, light/light_bvh.h): the patches are split into parts, each a leaf of the
//   BVH, so that a shading point picks the emitters near it. Within part j a patch is chosen by power, so
//   pdf_area = average(L_k) * sides_k / W_j. A ray that hits an emitting surface finds its patch (find(), a hash
//   grid over the patches) and so its part.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/bounds.h"
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
  /// Parts at most: above this many patches, runs of neighbouring patches (in Morton order) share a part, which
  /// bounds the light BVH's size (two nodes per part).
  static constexpr size_t kMaxParts = size_t(1) << 17;

  void add_parallelogram(Vec3f p, Vec3f e1, Vec3f e2, Vec3f n, Rgb radiance, bool two_sided);
  void add_triangle(Vec3f p0, Vec3f p1, Vec3f p2, Rgb radiance, bool two_sided);
  // Builds the selection tables, the parts and the hash grid of find(); call once after the last add. Throws
  // torte::Error when nothing emits.
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

  /// Number of parts (each patch belongs to one: patches [part * per_part, min((part + 1) * per_part, size()))).
  size_t part_count() const { return part_weight_.size(); }
  uint32_t part_of(size_t patch) const { return uint32_t(patch / per_part_); }
  size_t part_begin(uint32_t part) const { return size_t(part) * per_part_; }
  size_t part_end(uint32_t part) const { return std::min(patches_.size(), (size_t(part) + 1) * per_part_); }
  /// Power / pi of one part (the sum of its patches' weights).
  float part_weight(uint32_t part) const { return part_weight_[part]; }
  /// A point of part `part` chosen as the whole light chooses one, restricted to the part: pdf_area is the
  /// density given that part.
  PatchPoint sample_part(uint32_t part, Vec2f u) const;
  /// Density per unit area of a point on patch k given its part (what sample_part reports there).
  float pdf_area_in_part(size_t k) const;
  /// The patch that holds point q (up to rounding: q a little off its plane or its edges), or -1. Where patches
  /// meet, the one whose plane is closest.
  int64_t find(Vec3f q) const;

 private:
  struct Cell {
    int32_t x, y, z;
    uint32_t patch;
  };
  std::vector<EmissivePatch> patches_;
  Distribution1D select_;
  double total_weight_ = 0;
  size_t per_part_ = 1;
  std::vector<float> part_weight_;
  std::vector<float> part_cdf_;  // per patch: the weights of its part up to and including it, over the part's
  float cell_size_ = 1;         // hash grid of find(): cells at least as large as any patch
  std::vector<Cell> cells_;     // (cell, patch) for every cell a patch's box touches, sorted by cell
};

}  // namespace torte
