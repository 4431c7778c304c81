// The path-traced reference of the Cornell-like box (cornell_like.h) that the bidirectional integrators' tests
// (test_bdpt, test_vcm) converge to, and what they measure against it.
#pragma once
#include <cmath>
#include <cstdlib>
#include <string>

#include "cornell_like.h"
#include "scene_helpers.h"

namespace torte::test {

/// True in sanitizer builds (TORTE_TEST_REDUCED): heavy cases run with fewer samples and looser bounds.
inline bool reduced() {
  const char* v = std::getenv("TORTE_TEST_REDUCED");
  return v && std::string(v) != "0";
}

/// Root-mean-square difference of the pixels' channel averages (same-size images).
inline double rmse(const Image& a, const Image& b) {
  double sum = 0;
  for (size_t k = 0; k < a.pixels.size(); ++k) {
    const double d = a.pixels[k].average() - b.pixels[k].average();
    sum += d * d;
  }
  return std::sqrt(sum / double(a.pixels.size()));
}

/// Path tracing of the Cornell-like box, 64x64 at 4096 spp (16x16 tile means to about 0.1 %), seed 7; rendered
/// once per test process.
inline const Image& path_reference() {
  static const Image img = [] {
    RenderSettings p = integrator_settings(IntegratorKind::Path, 64, reduced() ? 512 : 4096);
    p.seed = 7;
    return render_view(*cornell_like(), box_camera(), p).image;
  }();
  return img;
}

}  // namespace torte::test
