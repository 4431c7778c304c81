// Many-light sampling: a BVH over the bounded lights (pbrt-v4's BVHLightSampler after Conty Estevez and Kulla
// 2018). A Patches light (a voxel world's emitters) is not one leaf but one leaf per part of its patches
// (EmissivePatches::part_count; one patch each below kMaxParts), so the descent finds the torch next to a point
// rather than a box around the whole world. Each node bounds its lights' positions, their emission directions
// (a cone around w of half angle theta_o, widened by theta_e for the spread of emission off each normal) and
// their power; at a receiving point the sampler descends choosing each child by its importance (power over
// squared distance, times how far the point lies inside the cones), so a light far away or facing away is seldom
// chosen. Lights at infinity (and directional lights) cannot be bounded: they are chosen (uniformly among them)
// with a probability that weighs their irradiance against the bounded lights' (a grid near them, weighed by
// visibility at scene build; the root's importance further away), clamped to [kMinShare, 1 - kMinShare]; pbrt's
// fixed n_inf / (n_inf + 1) gave a faint sky half of all samples, the root's importance alone gave a sunlit
// Minecraft surface's samples to lava lakes buried under it.
//
// Deterministic, no allocation per query, read-only after the build and weigh_visibility (shared by all threads).
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/bounds.h"
#include "core/ray.h"
#include "core/vec.h"
#include "light/light.h"

namespace torte {

/// A cone of directions: the unit axis w and the cosine of its half angle (-1: every direction).
struct DirectionCone {
  Vec3f w{0, 0, 1};
  float cos_theta = 1;
  bool empty = true;
  static DirectionCone everywhere() { return {{0, 0, 1}, -1, false}; }
};
/// The smallest cone holding both (pbrt-v4's Union).
DirectionCone merge(const DirectionCone& a, const DirectionCone& b);

/// What the sampler knows of a light or a group of lights.
struct LightBounds {
  Bounds3f bounds;
  float phi = 0;              // power (any consistent unit: the sampler only compares)
  DirectionCone normals;      // directions of the emitting surfaces' normals (or a spot's axis)
  float cos_theta_e = 0;      // emission spreads this far off each normal: cos(pi/2) for diffuse, a spot's cone
  bool two_sided = false;
  /// Importance of the group for a receiver at p with normal n (n = 0: no receiver cosine): 0 when no light of
  /// it can reach p. Conservative: never 0 for a light that can. The squared distance is clamped at min_d2 (and
  /// at an eighth of the box's diagonal, squared).
  float importance(Vec3f p, Vec3f n, float min_d2 = 0) const;
};

/// The bounds of `light` for the sampler, or bounds with phi = 0 for lights at infinity, directional lights
/// and lights of no power (those the BVH leaves out). For a Patches light, `part` picks one of its parts (the
/// whole light with kWholeLight) and `power` is ignored: a part's power is pi times its weight.
LightBounds light_bounds(const EmitterView& scene, const Light& light, float power, uint32_t part = kWholeLight);

class LightBvh {
 public:
  LightBvh() = default;
  /// Builds over `lights` (`power[i]` from light_power): bounded lights of positive power in the BVH (binned
  /// surface-area-orientation heuristic), lights at infinity beside it; uniform infinite lights are left to BSDF
  /// sampling (never chosen, pmf 0).
  LightBvh(const EmitterView& scene, std::span<const Light> lights, std::span<const float> power);

  bool empty() const { return light_count_ == 0; }
  /// A light for a receiver at p (normal n, or 0) from one uniform number u in [0, 1); its probability in *pmf
  /// and in *part which part of it (a Patches light's, to pass to sample_light; 0 for other kinds). -1 (pmf 0)
  /// when no light can reach p.
  int sample(Vec3f p, Vec3f n, float u, float* pmf, uint32_t* part) const;
  /// sample() for `count` receivers at once: light[k], pmf[k] and part[k] are what sample(p[k], n[k], u[k], ...)
  /// gives, bit for bit where sample() is compiled without fused multiply-adds (simd/light_bvh_batch.h). The
  /// descents run side by side in vector lanes: one at a time, their dependent loads and unpredictable branches
  /// made a shading point's light sample cost twice its BSDF's.
  void sample_batch(size_t count, const Vec3f* p, const Vec3f* n, const float* u, int* light, float* pmf,
                    uint32_t* part) const;
  /// The probability that sample(p, n, ...) returns `light` and `part` (0 but for Patches lights).
  float pmf(Vec3f p, Vec3f n, int light, uint32_t part = 0) const;
  size_t node_count() const { return packed_.size(); }
  /// The probability that sample(p, n, ...) picks a light at infinity (0 without any, 1 without bounded lights
  /// or when none of them can reach p).
  float infinite_probability(Vec3f p, Vec3f n) const;
  /// The least share of samples either side gets when both exist.
  static constexpr float kMinShare = 0.02f;
  /// The irradiance grid's cells at most (see infinite_probability and weigh_visibility).
  static constexpr size_t kGridCells = size_t(1) << 16;
  /// Shadow rays per grid cell and side in weigh_visibility.
  static constexpr int kVisibilityRays = 4;
  /// The least visible fraction weigh_visibility gives either side ((seen + 1/4) / (rays + 1/4) otherwise).
  static constexpr float kVisibilityFloor = 0.25f / (kVisibilityRays + 0.25f);
  /// Weighs the grid behind infinite_probability by visibility: from random points of each cell, shadow rays
  /// (`occluded`, a scene's occlusion test) towards bounded lights chosen as sample() chooses them and towards
  /// the lights at infinity. Scene building only (deterministic; `scene` and `lights` as given to the constructor).
  void weigh_visibility(const EmitterView& scene, std::span<const Light> lights,
                        const std::function<bool(const Ray&)>& occluded);

  /// What the descent reads of a node: 48 bytes, a node's two children side by side, so that a step of the
  /// descent reads one pair of neighbours instead of two 72-byte build nodes far apart (the build's are dropped).
  struct PackedNode {
    Vec3f center;
    float phi = 0;
    Vec3f w{0, 0, 1};       // the normal cone's axis
    float cos_o = 1;        // and the cosine of its half angle
    float diag2 = 0;        // the box's squared diagonal
    float cos_e = 0;
    uint32_t index = 0;     // inner: the first of its two children (the second follows); leaf: the light
    uint32_t part_bits = 0;  // leaf: the light's part | kLeaf; kTwoSided on any node
    static constexpr uint32_t kLeaf = 1u << 31, kTwoSided = 1u << 30;
    bool leaf() const { return (part_bits & kLeaf) != 0; }
    uint32_t part() const { return part_bits & ~(kLeaf | kTwoSided); }
  };
  static PackedNode pack(const LightBounds& b);
  /// LightBounds::importance of the node packed from b (the same value).
  static float importance(const PackedNode& nd, Vec3f p, Vec3f n, float min_d2 = 0);

 private:
  struct Node {  // the build's tree (depth first: the first child follows the node), repacked into packed_
    LightBounds bounds;
    uint32_t child_or_light = 0;  // inner: index of the second child; leaf: light
    uint32_t part = 0;            // leaf: the light's part
    bool leaf = false;
  };
  struct Item {  // a leaf: a light, or one part of a Patches light
    uint32_t light, part;
  };
  // The build's tree goes into `nodes` (a local of the constructor: repack() makes packed_ of it).
  uint32_t build(std::vector<Node>& nodes, std::vector<uint32_t>& ids, size_t begin, size_t end,
                 const std::vector<LightBounds>& all, const std::vector<Item>& items, uint64_t trail, int depth);
  void build_grid(const Bounds3f& root);
  int sample_bounded(Vec3f p, Vec3f n, float u, float prob, float* pmf, uint32_t* part) const;
  size_t grid_cell(Vec3f p) const;  // the cell holding p, or SIZE_MAX outside the grid
  float cut_irradiance(Vec3f c, float min_d2) const;
  void repack(const std::vector<Node>& nodes);
  std::vector<PackedNode> packed_;   // the root, then pairs of siblings
  std::vector<uint32_t> infinite_;      // indices of the lights at infinity
  std::vector<uint32_t> first_item_;    // per light: its first item (its parts follow)
  std::vector<uint32_t> item_count_;    // per light: how many items it has (0 when not in the BVH)
  std::vector<uint64_t> trail_;         // per item: the branch bits from the root (bit d: second child at depth d)
  std::vector<uint8_t> in_bvh_;         // per light: 1 in the BVH, 2 at infinity, 0 never chosen
  size_t light_count_ = 0;
  float infinite_irradiance_ = 0;  // what the lights at infinity give a surface facing them, summed
  // The light when the BVH is one leaf and no light is at infinity: it is then always chosen, even where its
  // bounds say it cannot reach (its sample carries no light there), so no query computes an importance: for a
  // one-light scene such as the Cornell box that was 6 % of the render.
  int only_light_ = -1;
  uint32_t only_part_ = 0;
  // Near the bounded lights the root's importance (their power as if at the root's centre) says little of where
  // they are: there the bounded irradiance comes from a grid, each cell summing a cut of the tree at its centre,
  // times the fraction of shadow rays towards them that arrive (weigh_visibility); the lights at infinity's
  // irradiance is weighed by their fraction (grid_sky_).
  Bounds3f grid_box_;
  int grid_n_[3] = {0, 0, 0};
  float grid_cell_ = 0, grid_inv_cell_ = 0;
  std::vector<float> grid_, grid_sky_;
};

}  // namespace torte
