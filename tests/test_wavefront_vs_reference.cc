// The wavefront renderer (type-sorted queues, phased shading kernels, SIMD BSDF evaluation) against the per-hit
// reference path tracer of reference_path_tracer.h (recursive, one ray at a time, virtual BSDF dispatch per hit)
// on a room holding Lambert, Oren-Nayar, mirror, rough metal, glass and plastic: tile means must agree within
// their noise. The tolerance is statistical (4 standard errors from per-pixel sample variances, plus 1%), and
// the test shows that it can fail: a reference whose metal BSDF is twice too bright is detected.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <sstream>

#include "material_room.h"
#include "reference_path_tracer.h"
#include "render/render.h"
#include "scene_helpers.h"
#include "scene/builder.h"

using namespace torte;

namespace {

struct TileComparison {
  int tiles = 0, outliers = 0;
  double max_z = 0;
  std::string worst;
};

// Per tile and channel: the wavefront's and the reference's tile means, with standard errors from the
// reference's per-pixel sample variances (the wavefront's QMC samples have at most that variance per sample).
TileComparison compare_tiles(const Image& wf, int wf_spp, const std::vector<reference::PixelEstimate>& ref,
                             int ref_spp, int tile) {
  TileComparison out;
  for (int y0 = 0; y0 < wf.height; y0 += tile)
    for (int x0 = 0; x0 < wf.width; x0 += tile)
      for (int c = 0; c < 3; ++c) {
        double a = 0, b = 0, var_b = 0;
        int n = 0;
        for (int y = y0; y < std::min(y0 + tile, wf.height); ++y)
          for (int x = x0; x < std::min(x0 + tile, wf.width); ++x) {
            const Rgb& w = wf.at(x, y);
            const reference::PixelEstimate& r = ref[size_t(y) * wf.width + x];
            a += c == 0 ? w.r : c == 1 ? w.g : w.b;
            b += c == 0 ? r.mean.r : c == 1 ? r.mean.g : r.mean.b;
            var_b += c == 0 ? r.var_of_mean.r : c == 1 ? r.var_of_mean.g : r.var_of_mean.b;
            ++n;
          }
        a /= n;
        b /= n;
        var_b /= double(n) * n;
        const double var_a = var_b * ref_spp / wf_spp;
        const double se = std::sqrt(var_a + var_b);
        const double diff = std::fabs(a - b);
        const double z = diff / (se + 1e-12);
        ++out.tiles;
        if (diff > 4 * se + 0.01 * std::max(a, b) + 1e-5) ++out.outliers;
        if (z > out.max_z) {
          out.max_z = z;
          std::ostringstream s;
          s << "tile (" << x0 << ", " << y0 << ") channel " << c << ": wavefront " << a << ", reference " << b
            << ", standard error " << se;
          out.worst = s.str();
        }
      }
  return out;
}

}  // namespace

TEST_CASE("wavefront render equals the per-hit reference path tracer within noise", "[render][reference]") {
  const auto scene = test::material_room();
  RenderSettings s;
  s.width = s.height = 32;
  s.spp = 256;
  s.max_depth = 12;
  s.seed = 3;
  const CameraDesc cam = test::material_room_camera();
  const Image wf = render(*scene, Camera(cam, s.width, s.height), s).image;
  const int ref_spp = 512;
  const reference::PathTracer reference(*scene, cam, s);
  const auto ref = reference.render(ref_spp, 11);

  const TileComparison cmp = compare_tiles(wf, s.spp, ref, ref_spp, 8);
  INFO("worst " << cmp.worst << " (" << cmp.max_z << " standard errors), outliers " << cmp.outliers << " of "
                << cmp.tiles);
  CHECK(cmp.outliers == 0);
  double mean = 0;
  for (const Rgb& p : wf.pixels) mean += p.g;
  CHECK(mean / double(wf.pixels.size()) > 0.02);  // lit

  SECTION("and a wrong BSDF in the reference is detected: metal twice too bright") {
    reference::Options bad;
    bad.scaled_type = MaterialType::Conductor;
    bad.scale = 2;
    const reference::PathTracer wrong(*scene, cam, s, bad);
    const auto ref_bad = wrong.render(128, 12);
    const TileComparison bad_cmp = compare_tiles(wf, s.spp, ref_bad, 128, 8);
    INFO("worst " << bad_cmp.worst << " (" << bad_cmp.max_z << " standard errors)");
    CHECK(bad_cmp.outliers > 0);
  }
}
