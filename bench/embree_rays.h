// Embree's side of embree-compare: its scene over a torte mesh (shared buffers, Embree's default triangle
// builder at medium quality), and the same ray batches traced with rtcIntersect/rtcOccluded 1 and 16, each
// writing what torte's kernels write (Hit records, occlusion bytes), so the two are timed doing the same work.
#pragma once
#include <embree3/rtcore.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "accel/hit.h"
#include "geometry/mesh.h"
#include "workloads.h"

namespace torte::bench {

/// Bytes Embree has allocated and their peak, kept by embree_memory_monitor (set it on the device).
extern std::atomic<int64_t> g_embree_bytes, g_embree_peak;
bool embree_memory_monitor(void*, ssize_t bytes, bool);
/// Device error callback: prints the error and exits with status 3.
void embree_error(void*, RTCError code, const char* str);

/// Embree's scene over `mesh` whose positions are `vertices` (x, y, z per vertex and one float of padding);
/// `robust` sets RTC_SCENE_FLAG_ROBUST. The caller releases it.
RTCScene build_embree(RTCDevice dev, const std::vector<float>& vertices, const TriangleMesh& mesh, bool robust);

/// Closest hits of rays [b, e) into out[b, e), one ray (1) or packets of 16 at a time; `t_only` keeps only t
/// (the harness before 2026-11-23), `coherent` sets the context's COHERENT flag.
void embree_closest1(RTCScene scene, const RayBatch& rays, size_t b, size_t e, Hit* out, bool t_only);
void embree_closest16(RTCScene scene, const RayBatch& rays, size_t b, size_t e, Hit* out, bool coherent,
                      bool t_only);
/// occ[i] = 1 when ray i of [b, e) is blocked.
void embree_any1(RTCScene scene, const RayBatch& rays, size_t b, size_t e, uint8_t* occ);
void embree_any16(RTCScene scene, const RayBatch& rays, size_t b, size_t e, uint8_t* occ, bool coherent);

}  // namespace torte::bench
