// The flattened, immutable scene the renderer reads: world-space SoA meshes, transformed analytic shapes, their
// BVHs, instanced prototypes with a top-level BVH over the instances, material tables and lights. Built by
// SceneBuilder::flatten; it holds no camera, so one build serves renders from any view.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "accel/aggregate.h"
#include "core/sampling.h"
#include "geometry/mesh.h"
#include "geometry/quadric.h"
#include "light/light.h"
#include "light/light_bvh.h"
#include "material/material.h"
#include "texture/texture.h"

namespace torte {

// Hit (accel/hit.h): prim is a primitive id within its geometry set ([0, triangle_count) triangles, then
// quadrics); instance is kNoHit for the scene's own shapes, else the index in Scene::instances.

// One placed shape (a mesh or a quadric) with its material and, if it emits, its area light.
struct SceneObject {
  MaterialRef material;
  int32_t area_light = -1;  // index into Scene::lights, -1 if the object does not emit
  int32_t alpha_mask = -1;  // index into Scene::alpha_masks, -1 if the object is opaque
};

/// Cut-outs (torte.material.mask, glTF's alphaMode): where `alpha` is below `cutoff` the surface is not there,
/// for every ray (camera, extension and shadow rays pass it). `stochastic`: present with probability alpha
/// instead (glTF's BLEND), decided by a hash of the hit so the same ray decides the same way.
struct AlphaMask {
  FloatParam alpha{1.0f};
  float cutoff = 0.5f;
  bool stochastic = false;
};

// SurfaceEmission (an override's emission) and EmitterView are in light/light.h.

// Prototype and Instance (the two levels of instancing) are in accel/aggregate.h.

class Scene;
/// Why every image of `scene` is black whatever the camera sees ("the scene has no lights and no emitting
/// shapes"), or "" when something may be lit. For a warning: such a scene is legitimate.
std::string black_image_reason(const Scene& scene);

class Scene {
 public:
  // The scene's own shapes in world space; object i is meshes[i] for i < meshes.size(), then quadrics, then
  // the objects of the prototypes (each prototype's objects numbered from its geometry's object base).
  // finalize() reorders every mesh's triangles (geometry_set.h) and releases the positions of all meshes but
  // area lights': from then on surface() is the way to a triangle's vertices.
  std::vector<TriangleMesh> meshes;
  std::vector<Quadric> quadrics;
  std::vector<VoxelGridAccel> grids;  // voxel grids: objects after the quadrics (voxel/voxel_accel.h)
  std::vector<SceneObject> objects;
  // Materials that replace an object's for part of it (SurfaceHit::material): voxel faces and cell shapes.
  std::vector<MaterialRef> material_overrides;
  // Parallel to material_overrides up to the last emitting override (shorter, usually empty, otherwise).
  std::vector<SurfaceEmission> override_emission;
  // The material at a hit: the voxel face's override when it has one, else its object's.
  MaterialRef material_of(const SurfaceHit& s) const {
    return s.material >= 0 ? material_overrides[size_t(s.material)] : objects[s.object].material;
  }
  // Instancing (two levels): prototypes shared by many instances. Held by pointer: each geometry set points
  // into its prototype's arrays.
  std::vector<std::unique_ptr<Prototype>> prototypes;
  std::vector<Instance> instances;
  MaterialTables materials;
  std::vector<AlphaMask> alpha_masks;
  TextureTable textures;
  std::vector<Light> lights;
  std::vector<uint32_t> infinite_lights;  // indices of the lights at infinity (what escaped rays see); finalize()
  Distribution1D light_selection;  // light selection proportional to power (light paths; NEE with "power")
  LightBvh light_bvh;              // light selection for a shading point (NEE; light/light_bvh.h)

  /// The triangles' layout (accel/accel_options.h: bvh_layout, memory_budget), read by finalize().
  AccelOptions accel_options;

  // Builds the BVHs (top-level geometry, every prototype, the instance level) and the light distribution; call
  // after filling the arrays above.
  // `progress` (optional): its total is set to GeometrySet::kProgressPerTriangle units per triangle of the scene,
  // which the builds add up.
  void finalize(ProgressCounter* progress = nullptr);

  // Top-level (non-instanced) geometry.
  uint32_t triangle_count() const { return accel_.root().triangle_count(); }
  uint32_t primitive_count() const { return accel_.root().primitive_count(); }
  uint32_t object_of(uint32_t prim) const { return accel_.root().object_of(prim); }
  Bounds3f bounds() const { return bounds_; }
  // Bounding sphere of the scene (for infinite lights).
  Vec3f center() const { return center_; }
  float radius() const { return radius_; }
  /// What light code reads (light/light.h); implicit, so light functions take a Scene where they take a view.
  EmitterView emitters() const { return {meshes, quadrics, override_emission, center_, radius_, &textures}; }
  operator EmitterView() const { return emitters(); }

  // One ray (tests, light tools). The renderer traces whole batches with the functions below.
  bool intersect(Ray& ray, Hit* hit) const;
  /// The same, adding the search's nodes and primitive tests to *cost (Aggregate::intersect_counted; the
  /// continuation past alpha cut-outs is not counted); without `cost`, the function above.
  bool intersect(Ray& ray, Hit* hit, TraversalCost* cost) const;
  bool occluded(const Ray& ray) const;
  // Batches: `coherent` rays (neighbours in groups of 8, such as a tile's camera rays) go through the packet
  // kernels, others one ray at a time through the SIMD single-ray kernels.
  void intersect(const RaySoA& rays, size_t count, Hit* hits, bool coherent) const;
  void occluded(const RaySoA& rays, size_t count, uint8_t* occluded, bool coherent) const;
  // The hit's surface in world space (instances map points, normals and tangents to the world).
  SurfaceHit surface(const Ray& ray, const Hit& hit) const;
  /// Both levels of tracing (accel/aggregate.h), which the functions above forward to.
  const Aggregate& accel() const { return accel_; }
  // Bytes of acceleration data (wide BVH nodes, leaf triangles, index maps, quadric and instance BVHs), all
  // levels, prototypes counted once.
  size_t accel_bytes() const;
  // Bytes of geometry (mesh arrays, quadrics), prototypes counted once, plus the instance records.
  size_t geometry_bytes() const;

 private:
  void release_positions();
  // Alpha masks: whether hit h of ray r is on a cut-out point; closest hits moved past cut-out points (rays
  // traced again from just beyond them, at most kMaxAlphaLayers times).
  bool cut_out(const Ray& r, const Hit& h) const;
  void pass_cut_outs(const RaySoA& rays, size_t count, Hit* hits) const;
  void occluded_past_cut_outs(const RaySoA& rays, size_t count, uint8_t* blocked) const;
  Aggregate accel_;  // both levels of tracing; the forwards above are its seam to the renderer
  Bounds3f bounds_;
  Vec3f center_;
  float radius_ = 0;
};

}  // namespace torte
