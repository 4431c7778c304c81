// Lights as plain data, one record type with a kind tag: sampling switches on the kind (a predictable branch,
// not a virtual call). Area lights reference a scene object (a mesh or a quadric); environment maps and the sky
// keep their tables behind shared pointers, so copying a Light stays cheap.
//
// Kinds:
//   Point        position, intensity `radiance` (W/sr). Delta.
//   Spot         position, axis `direction`, intensity `radiance` (W/sr on the axis), cone: full intensity inside
//                cos_falloff_start, smoothstep down to zero at cos_total (pbrt-v4). Delta.
//   Distant      parallel light travelling along `direction`; `radiance` is the irradiance (W/m^2) on a surface
//                facing it. Delta.
//   Area         diffuse emitter on a scene object. Spheres under a similarity transform are sampled by solid angle
//                (uniform in the cone of the sphere seen from outside); other shapes, and points inside a
//                sphere, by area.
//   Infinite     uniform radiance from every direction.
//   Environment  equirectangular image (light/environment.h), importance-sampled over the whole sphere.
//   Sky          Preetham sky plus sun disk (light/sky.h).
//   Patches      many small diffuse emitters in world space, chosen by power (light/emissive_patches.h): the
//                faces of emitting voxels and the emitting shapes in voxel cells.
// Infinite, Environment and Sky are "infinite-like": rays that escape the scene see escaped_radiance().
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "core/rgb.h"
#include "core/sampling.h"
#include "core/transform.h"
#include "core/vec.h"
#include "geometry/mesh.h"
#include "geometry/quadric.h"
#include "light/emissive_patches.h"
#include "light/environment.h"
#include "light/sky.h"
#include "texture/texture_param.h"

namespace torte {

struct SurfaceHit;
class TextureTable;

// Emission of a material override (a voxel face or an object of a voxel cell shape) that belongs to a Patches
// light: what a ray hitting it sees, and which light samples it.
struct SurfaceEmission {
  Rgb radiance;
  int32_t light = -1;  // index into the scene's lights (a LightKind::Patches light), -1 = does not emit
  bool two_sided = false;
};

/// What light code reads of a scene: the shapes area lights sit on (scene objects: meshes[i] for i <
/// meshes.size(), then quadrics), the emission of material overrides, and the bounding sphere (lights at
/// infinity). A view: the scene owns the arrays and must outlive it. The Scene converts to one (scene/scene.h).
struct EmitterView {
  std::span<const TriangleMesh> meshes;
  std::span<const Quadric> quadrics;
  std::span<const SurfaceEmission> override_emission;
  Vec3f center;
  float radius = 0;
  const TextureTable* textures = nullptr;  // for textured area lights (Light::emission_texture)
};

enum class LightKind : uint8_t { Point, Area, Infinite, Spot, Distant, Environment, Sky, Patches };

/// A triangle of an emitting mesh as light sampling reads it: a vertex, the two edges from it and the unit normal
/// of its winding, in world space. A point at barycentrics (b1, b2) is p0 + e1 b1 + e2 b2.
struct EmitterTriangle {
  Vec3f p0, e1, e2, n;
};
static_assert(sizeof(EmitterTriangle) == 48);

struct Light {
  LightKind kind = LightKind::Point;
  Rgb radiance;          // point/spot: intensity (W/sr); area: emitted radiance; infinite: radiance from every
                         // direction; distant: irradiance
  Vec3f position;        // point, spot
  Vec3f direction{0, 0, 1};  // spot: cone axis (unit); distant: direction the light travels (unit)
  float cos_total = 0;          // spot: cosine of the cone's half angle (no light beyond)
  float cos_falloff_start = 1;  // spot: cosine of the half angle where the falloff starts
  uint32_t object = 0;   // area: emitting scene object
  // area: `radiance` times this texture at the point (a constant, or a node of the scene's TextureTable)
  ColorParam emission_texture{Rgb(1)};
  bool two_sided = false;  // area: emits on both sides
  float area = 0;        // area: total world area
  Distribution1D triangles;  // area light on a mesh: triangle selection by area
  // Area light on a mesh: its triangles ready to sample, so a light sample reads one record instead of an index
  // triple and three vertices through the mesh (a tenth of a Cornell box's render time went there).
  std::vector<EmitterTriangle> emitter_triangles;
  // Area light on a sphere under a similarity transform (set by prepare_sphere_light): solid-angle sampling.
  bool sphere_cone = false;
  Vec3f sphere_center;
  float sphere_radius = 0;
  std::shared_ptr<const EnvironmentMap> environment;  // Environment
  std::shared_ptr<const SkyModel> sky;                // Sky
  std::shared_ptr<const EmissivePatches> patches;     // Patches
  std::string origin;  // where the script made it ("torte.light.point at scene.lua:12"), for messages; may be empty
};

/// The light as one placement of its group puts it in the world (instancing): positions map as points, directions
/// as vectors (renormalized); intensities and the spot cone's angles stay. Point, Spot and Distant lights only:
/// throws torte::Error for the others (lights at infinity and emitters cannot be placed by an instance).
Light placed_light(const Light& light, const Transform& to_world);
/// "point", "spot", "directional", ...
const char* light_kind_name(LightKind kind);
/// The light's origin ("torte.light.point at scene.lua:12"), or "a point light" when it is unknown.
std::string light_name(const Light& light);

struct LightSample {
  Rgb radiance;     // arriving radiance (or intensity / d^2 for point lights)
  Vec3f wi;         // unit direction from the shading point towards the light
  float distance;   // to the light point (kInfinity for infinite and distant lights)
  float pdf;        // solid-angle density; for delta lights the probability (1)
  bool delta;       // true for point, spot and distant lights: BSDF sampling cannot hit them
};

// A point on an area light chosen uniformly by area (a triangle by area, then a uniform point; or the quadric's
// area sampling): position, the emitting side's normal (the winding's, turned to the interpolated normal's side
// when the mesh has normals: the side area_emission lets emit) and the density per unit area.
// `uv` (optional): the point's surface parameterisation, for textured emission.
void sample_area_light_point(const EmitterView& scene, const Light& light, Vec2f u, Vec3f* q, Vec3f* n, float* pdf_area,
                             Vec2f* uv = nullptr);
/// The radiance an area light emits at a point of its surface (p, n, uv): its constant times its texture there.
Rgb area_radiance(const EmitterView& scene, const Light& light, Vec3f p, Vec3f n, Vec2f uv);

/// `part` of sample_light: the whole light (the only choice but for Patches lights).
constexpr uint32_t kWholeLight = 0xffffffffu;
// Samples light `l` as seen from point p. Returns false when the sample carries no light. `part`: for a Patches
// light, one of its parts (EmissivePatches::part_count; the light BVH picks them), s->pdf then the density given
// that part; ignored by other kinds.
bool sample_light(const EmitterView& scene, const Light& light, Vec3f p, Vec2f u, LightSample* s,
                  uint32_t part = kWholeLight);
// Solid-angle density with which sample_light would have chosen direction wi from p, given that the ray hit
// `hit` on this area light (for area lights), or escaped (infinite-like lights). 0 for delta lights.
float light_pdf(const EmitterView& scene, const Light& light, Vec3f p, Vec3f wi, const SurfaceHit* hit, float t);
/// For a ray from p along wi that hit Patches light `light` at `hit` (distance t): the patch's part in *part and
/// the solid-angle density with which sample_light(..., *part) would have chosen that direction; 0 when the hit
/// lies on none of the light's patches.
float patch_pdf_in_part(const Light& light, Vec3f p, Vec3f wi, const SurfaceHit& hit, float t, uint32_t* part);
// Radiance an area light emits from `hit` towards -w (w is the ray direction).
Rgb area_emission(const EmitterView& scene, const Light& light, const SurfaceHit& hit, Vec3f w);
// Emission of a surface that is part of a Patches light (a voxel face or cell shape): the scene's
// override_emission entry of its material override, or nullptr.
const SurfaceEmission* patch_emission(const EmitterView& scene, const SurfaceHit& hit);
// patch_emission when that surface emits towards -w (its emitting side, or either side when two-sided), else
// nullptr: what a ray along w that hits it sees.
const SurfaceEmission* patch_emission_towards(const EmitterView& scene, const SurfaceHit& hit, Vec3f w);
// True for lights that rays escaping the scene can see (Infinite, Environment, Sky).
inline bool is_infinite_light(const Light& light) {
  return light.kind == LightKind::Infinite || light.kind == LightKind::Environment || light.kind == LightKind::Sky;
}
// Radiance arriving along -dir from an infinite-like light for a ray with direction dir that escaped; black for
// other kinds.
Rgb escaped_radiance(const Light& light, Vec3f dir);
// Total emitted power, used to weight light selection (lights at infinity: the power through the scene's
// bounding sphere).
float light_power(const EmitterView& scene, const Light& light);
/// Sets an area light on `mesh` (world space) up for sampling: its total area, the triangle distribution by area and
/// the triangles' sampling records. False (and nothing usable set) when the mesh has zero area.
bool prepare_mesh_light(const TriangleMesh& mesh, Light* light);
// Enables solid-angle sampling for an area light on a sphere placed by a similarity transform (no-op otherwise).
void prepare_sphere_light(const Quadric& q, Light* light);
// Spot light intensity factor for a direction at cos_theta from the axis (smoothstep, pbrt-v4).
float spot_falloff(const Light& light, float cos_theta);
// Samples an emission direction of a spot light uniformly in its cone (for light tracing); *pdf: solid angle.
Vec3f sample_spot_emission(const Light& light, Vec2f u, float* pdf);

}  // namespace torte
