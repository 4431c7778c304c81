#include "embree_rays.h"

#include <cstdio>
#include <cstdlib>

namespace torte::bench {

std::atomic<int64_t> g_embree_bytes{0}, g_embree_peak{0};

bool embree_memory_monitor(void*, ssize_t bytes, bool) {
  const int64_t now = g_embree_bytes += bytes;
  int64_t peak = g_embree_peak.load();
  while (now > peak && !g_embree_peak.compare_exchange_weak(peak, now)) {
  }
  return true;
}

void embree_error(void*, RTCError code, const char* str) {
  std::fprintf(stderr, "embree-compare: Embree error %d: %s\n", int(code), str ? str : "");
  std::exit(3);
}

RTCScene build_embree(RTCDevice dev, const std::vector<float>& vertices, const TriangleMesh& mesh, bool robust) {
  RTCScene scene = rtcNewScene(dev);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  if (robust) rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_MEDIUM);
  // Shared buffers: Embree reads the caller's arrays in place (the vertex array carries one float of padding,
  // which Embree requires for its 16-byte loads; torte's index triples are used as they are).
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices.data(), 0, 12,
                             mesh.vertex_count());
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(), 0, 12,
                             mesh.triangle_count());
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(scene);
  return scene;
}

// Closest hits leave both sides with the same record: torte writes a Hit (t, primitive, barycentrics, instance;
// 20 bytes) per ray, and so does Embree's side here, from its RTCHit, which is what a renderer shading the hits
// needs from either. With --embree-hits t Embree's side keeps only t (the harness before 2026-11-23), which spares
// it 16 bytes of stores per ray that torte pays.
namespace {

inline void embree_hit(Hit* out, size_t i, bool hit, float t, uint32_t prim, float u, float v, uint32_t inst,
                       bool t_only) {
  if (t_only) out[i].t = hit ? t : kInfinity;
  else out[i] = hit ? Hit{t, prim, u, v, inst} : Hit{};
}

}  // namespace

void embree_closest1(RTCScene scene, const RayBatch& rays, size_t b, size_t e, Hit* out, bool t_only) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (size_t i = b; i < e; ++i) {
    RTCRayHit rh;
    rh.ray.org_x = rays.ox[i], rh.ray.org_y = rays.oy[i], rh.ray.org_z = rays.oz[i], rh.ray.tnear = 0;
    rh.ray.dir_x = rays.dx[i], rh.ray.dir_y = rays.dy[i], rh.ray.dir_z = rays.dz[i], rh.ray.time = 0;
    rh.ray.tfar = rays.t_max[i], rh.ray.mask = ~0u, rh.ray.id = uint32_t(i), rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
    embree_hit(out, i, rh.hit.geomID != RTC_INVALID_GEOMETRY_ID, rh.ray.tfar, rh.hit.primID, rh.hit.u, rh.hit.v,
               rh.hit.instID[0], t_only);
  }
}

void embree_any1(RTCScene scene, const RayBatch& rays, size_t b, size_t e, uint8_t* occ) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (size_t i = b; i < e; ++i) {
    RTCRay r;
    r.org_x = rays.ox[i], r.org_y = rays.oy[i], r.org_z = rays.oz[i], r.tnear = 0;
    r.dir_x = rays.dx[i], r.dir_y = rays.dy[i], r.dir_z = rays.dz[i], r.time = 0;
    r.tfar = rays.t_max[i], r.mask = ~0u, r.id = uint32_t(i), r.flags = 0;
    rtcOccluded1(scene, &ctx, &r);
    occ[i] = r.tfar < 0;  // Embree sets tfar = -inf for an occluded ray
  }
}

namespace {

// Loads rays [i, min(i + 16, e)) into a packet; the other lanes are invalid.
template <class Packet>
void load16(Packet& r, int* valid, const RayBatch& rays, size_t i, size_t e) {
  for (int k = 0; k < 16; ++k) {
    const size_t j = i + k;
    const bool ok = j < e;
    const size_t s = ok ? j : i;
    valid[k] = ok ? -1 : 0;
    r.org_x[k] = rays.ox[s], r.org_y[k] = rays.oy[s], r.org_z[k] = rays.oz[s], r.tnear[k] = 0;
    r.dir_x[k] = rays.dx[s], r.dir_y[k] = rays.dy[s], r.dir_z[k] = rays.dz[s], r.time[k] = 0;
    r.tfar[k] = rays.t_max[s], r.mask[k] = ~0u, r.id[k] = uint32_t(j), r.flags[k] = 0;
  }
}

// The context of a 16-ray call: Embree's coherent hint or its default (incoherent) mode.
RTCIntersectContext packet_context(bool coherent) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  if (coherent) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  return ctx;
}

}  // namespace

void embree_closest16(RTCScene scene, const RayBatch& rays, size_t b, size_t e, Hit* out, bool coherent,
                      bool t_only) {
  RTCIntersectContext ctx = packet_context(coherent);
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[16];
  for (size_t i = b; i < e; i += 16) {
    load16(rh.ray, valid, rays, i, e);
    for (int k = 0; k < 16; ++k) rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect16(valid, scene, &ctx, &rh);
    for (int k = 0; k < 16 && i + k < e; ++k)
      embree_hit(out, i + k, rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID, rh.ray.tfar[k], rh.hit.primID[k],
                 rh.hit.u[k], rh.hit.v[k], rh.hit.instID[0][k], t_only);
  }
}

void embree_any16(RTCScene scene, const RayBatch& rays, size_t b, size_t e, uint8_t* occ, bool coherent) {
  RTCIntersectContext ctx = packet_context(coherent);
  alignas(64) RTCRay16 r;
  alignas(64) int valid[16];
  for (size_t i = b; i < e; i += 16) {
    load16(r, valid, rays, i, e);
    rtcOccluded16(valid, scene, &ctx, &r);
    for (int k = 0; k < 16 && i + k < e; ++k) occ[i + k] = r.tfar[k] < 0;
  }
}

}  // namespace torte::bench
