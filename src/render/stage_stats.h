// The per-stage profile of a render (torte --stats, RenderSettings::stage_stats): for every stage of the
// wavefront its wall time summed over threads, its calls and the rays or items it processed. Times are taken
// once per stage call (a wavefront batch), never per ray; with the profile off no clock is read, and each
// stage boundary costs one predictable branch.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

#include "material/material.h"

namespace torte {

/// The profiled stages besides shading, which has one entry per shaded material type (StageStats::shade).
enum class Stage : uint8_t {
  VplPass,    // IGI: light paths traced from the lights and their VPLs built, before each pass
  Camera,     // camera ray generation
  Trace,      // extension rays (camera rays included) traced
  Hits,       // hit reconstruction, material resolution, counting sort by material type
  Emission,   // escaped rays and emitters hit: light found by the path's own rays
  Shadows,    // shadow rays traced (IGI's VPL shadow rays too)
  VplGather,  // IGI: shadow rays towards the VPLs queued at the shaded hits
  Connect,    // BDPT: every strategy of the subpaths evaluated and MIS-weighted, connection rays queued
  Film,       // finished paths added to the film
  Count
};
constexpr int kStageCount = int(Stage::Count);

/// One stage's totals: thread seconds, calls (batches) and rays or items.
struct StageTime {
  double seconds = 0;
  uint64_t calls = 0, items = 0;
  // Shadows only: of `tested` shadow rays (those of the camera integrators' next-event estimation), how many were
  // blocked. A light sampler whose rays are mostly blocked is choosing lights that cannot be seen.
  uint64_t blocked = 0, tested = 0;
  void add(const StageTime& o) {
    seconds += o.seconds;
    calls += o.calls;
    items += o.items;
    blocked += o.blocked;
    tested += o.tested;
  }
};

struct StageStats {
  bool enabled = false;  // set by the tile loop from RenderSettings::stage_stats
  int threads = 0;       // threads that rendered tiles (set when the render ends)
  StageTime stage[kStageCount];
  StageTime shade[kShadedMaterialTypeCount];  // indexed by MaterialType

  StageTime& operator[](Stage s) { return stage[int(s)]; }
  const StageTime& operator[](Stage s) const { return stage[int(s)]; }
  /// Sum of every stage's and every shading kernel's seconds.
  double total_seconds() const;
  void add(const StageStats& o) {
    for (int i = 0; i < kStageCount; ++i) stage[i].add(o.stage[i]);
    for (int i = 0; i < kShadedMaterialTypeCount; ++i) shade[i].add(o.shade[i]);
  }
};

/// The name --stats and Lua's image.stages use for a stage ("trace") or a shaded material type ("plastic").
const char* stage_name(Stage s);
const char* shade_stage_name(MaterialType t);

/// The --stats table: one line per stage (shading one per material type, "shade lambert"), each with seconds,
/// % of the stages' total, calls, items and for trace stages Mrays per thread-second; then the total against
/// threads x `wall_seconds`. Lines end with '\n'.
std::string format_stage_table(const StageStats& st, double wall_seconds);

/// Laps of one thread's stage calls: lap(t, items) adds the time since the previous lap (or start()) to `t`.
/// Consecutive stages share a clock reading. Disabled, it reads no clock.
class StageClock {
 public:
  explicit StageClock(bool enabled = false) : enabled_(enabled) {}
  void start() {
    if (enabled_) last_ = std::chrono::steady_clock::now();
  }
  void lap(StageTime& t, uint64_t items) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    t.seconds += std::chrono::duration<double>(now - last_).count();
    ++t.calls;
    t.items += items;
    last_ = now;
  }

 private:
  bool enabled_;
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace torte
