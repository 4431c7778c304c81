#include "render/stage_stats.h"

#include <cstdio>

namespace torte {

namespace {

// What a stage's items are, for the table's last columns.
const char* item_unit(Stage s) {
  switch (s) {
    case Stage::VplPass: return "light rays";
    case Stage::Camera: return "rays";
    case Stage::Trace: return "rays";
    case Stage::Hits: return "hits queued";
    case Stage::Emission: return "rays";
    case Stage::Shadows: return "rays";
    case Stage::VplGather: return "rays queued";
    case Stage::Connect: return "samples";
    case Stage::Film: return "samples";
    case Stage::Count: break;
  }
  return "";
}

bool traces_rays(Stage s) { return s == Stage::VplPass || s == Stage::Trace || s == Stage::Shadows; }

}  // namespace

const char* stage_name(Stage s) {
  switch (s) {
    case Stage::VplPass: return "vpl_pass";
    case Stage::Camera: return "camera";
    case Stage::Trace: return "trace";
    case Stage::Hits: return "hits";
    case Stage::Emission: return "emission";
    case Stage::Shadows: return "shadows";
    case Stage::VplGather: return "vpl_gather";
    case Stage::Connect: return "connect";
    case Stage::Film: return "film";
    case Stage::Count: break;
  }
  return "?";
}

// The names of torte.material's constructors (matte is lambert or oren_nayar by its sigma).
const char* shade_stage_name(MaterialType t) {
  switch (t) {
    case MaterialType::Lambert: return "lambert";
    case MaterialType::OrenNayar: return "oren_nayar";
    case MaterialType::Mirror: return "mirror";
    case MaterialType::Conductor: return "metal";
    case MaterialType::Dielectric: return "glass";
    case MaterialType::ThinDielectric: return "thin_glass";
    case MaterialType::CoatedDiffuse: return "plastic";
    default: break;
  }
  return "?";
}

double StageStats::total_seconds() const {
  double s = 0;
  for (const StageTime& t : stage) s += t.seconds;
  for (const StageTime& t : shade) s += t.seconds;
  return s;
}

std::string format_stage_table(const StageStats& st, double wall_seconds) {
  const double total = st.total_seconds();
  std::string out = "stage profile (seconds summed over threads):\n";
  char line[200];
  auto row = [&](const std::string& name, const StageTime& t, const char* unit, bool trace) {
    const double share = total > 0 ? 100 * t.seconds / total : 0;
    int n = std::snprintf(line, sizeof line, "  %-18s %10.4f s %5.1f %% %9llu calls %12llu %s", name.c_str(),
                          t.seconds, share, static_cast<unsigned long long>(t.calls),
                          static_cast<unsigned long long>(t.items), unit);
    if (trace && n > 0 && size_t(n) < sizeof line)
      n += std::snprintf(line + n, sizeof line - size_t(n), ", %.2f Mrays/s per thread",
                         t.seconds > 0 ? double(t.items) / t.seconds * 1e-6 : 0.0);
    if (t.tested > 0 && n > 0 && size_t(n) < sizeof line)
      std::snprintf(line + n, sizeof line - size_t(n), ", %.1f %% blocked",
                    100.0 * double(t.blocked) / double(t.tested));
    out += line;
    out += '\n';
  };
  for (int i = 0; i < kStageCount; ++i) {
    const Stage s = Stage(i);
    // IGI's and BDPT's own stages only for renders that ran them.
    if ((s == Stage::VplPass || s == Stage::VplGather || s == Stage::Connect) && st[s].calls == 0) continue;
    row(stage_name(s), st[s], item_unit(s), traces_rays(s));
    if (s == Stage::Emission)  // shading comes between emission and shadows, one line per type that was hit
      for (int t = 0; t < kShadedMaterialTypeCount; ++t)
        if (st.shade[t].calls != 0)
          row(std::string("shade ") + shade_stage_name(MaterialType(t)), st.shade[t], "hits", false);
  }
  const double budget = double(st.threads) * wall_seconds;
  std::snprintf(line, sizeof line,
                "  %-18s %10.4f s of %d threads x %.3f s wall (%.1f %%; the rest: tile setup, idle)\n", "total", total, st.threads, wall_seconds, budget > 0 ? 100 * total / budget : 0.0);
  out += line;
  return out;
}

}  // namespace torte
