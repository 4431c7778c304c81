// The per-stage profile (RenderSettings::stage_stats, torte --stats): its counts agree with RenderStats for
// every integrator, each shaded material type gets its own entry, times add up within threads x wall time,
// and collecting it changes nothing in the image.
#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <memory>

#include "render/render.h"
#include "render/stage_stats.h"
#include "scene/builder.h"
#include "scene_helpers.h"

using namespace torte;
using namespace torte::test;

namespace {

std::shared_ptr<MaterialDesc> material(MaterialType type, Rgb color) {
  auto m = std::make_shared<MaterialDesc>();
  m->type = type;
  m->color.value = color;
  return m;
}

// A matte floor, a plastic sphere and a glass sphere under a spherical area light and a dim sky (so some rays
// escape and find light): three shaded types, emission found both ways.
std::shared_ptr<Scene> three_material_scene() {
  SceneBuilder b;
  ShapeDesc floor;
  floor.kind = ShapeDesc::Kind::Mesh;
  floor.mesh = std::make_shared<TriangleMesh>(make_polygon({{-3, -1, -3}, {-3, -1, 3}, {3, -1, 3}, {3, -1, -3}}));
  floor.material = material(MaterialType::Lambert, Rgb(0.6f));
  b.add_shape(floor);
  const auto plastic = material(MaterialType::CoatedDiffuse, Rgb(0.7f, 0.2f, 0.1f));
  b.add_shape(sphere_shape(0.6f, translate({-0.7f, -0.4f, 0}), plastic));
  b.add_shape(sphere_shape(0.5f, translate({0.7f, -0.5f, 0}), material(MaterialType::Dielectric, Rgb(1))));
  ShapeDesc lamp = sphere_shape(0.3f, translate({0, 1.5f, -0.5f}), matte(0));
  lamp.emission = Rgb(15);
  b.add_shape(lamp);
  b.add_light(uniform_sky(Rgb(0.2f)));
  return b.flatten();
}

const CameraDesc kCamera = camera_at({0, 0.5f, -4}, {0, -0.3f, 0}, 45);

RenderSettings settings(IntegratorKind k, bool stats) {
  RenderSettings s;
  s.width = 40;
  s.height = 24;
  s.spp = 6;
  s.max_depth = 6;
  s.integrator = k;
  s.sample_all_lights = k != IntegratorKind::Path;
  s.light_paths = 16;
  s.stage_stats = stats;
  return s;
}

uint64_t shaded_hits(const StageStats& st) {
  uint64_t n = 0;
  for (const StageTime& t : st.shade) n += t.items;
  return n;
}

// Every count of the profile against RenderStats' own counters, and the times against threads x wall.
void check_consistent(const RenderStats& r, IntegratorKind k, const RenderSettings& s) {
  const StageStats& st = r.stages;
  REQUIRE(st.enabled);
  const uint64_t samples = uint64_t(s.width) * s.height * s.spp;
  CHECK(r.samples_done == samples);
  CHECK(st[Stage::Camera].items == r.camera_rays);
  CHECK(st[Stage::Film].items == r.samples_done);
  CHECK(st[Stage::Camera].calls == st[Stage::Film].calls);  // one of each per wavefront batch
  // Every ray traced by a stage: camera and extension rays by the trace stage (and IGI's light paths by its
  // VPL pass), shadow rays by the shadow stage.
  CHECK(st[Stage::Trace].items + st[Stage::VplPass].items == r.camera_rays + r.extension_rays);
  CHECK(st[Stage::Shadows].items == r.shadow_rays);
  CHECK(st[Stage::Trace].items + st[Stage::Shadows].items + st[Stage::VplPass].items == r.rays());
  // One trace, sort and emission call per bounce; every ray traced is looked at for emission.
  CHECK(st[Stage::Hits].calls == st[Stage::Trace].calls);
  CHECK(st[Stage::Emission].calls == st[Stage::Trace].calls);
  CHECK(st[Stage::Emission].items == st[Stage::Trace].items);
  // The hits queued for shading are the hits shaded, type by type; every queued hit came from a traced ray.
  CHECK(shaded_hits(st) == st[Stage::Hits].items);
  CHECK(st[Stage::Hits].items <= st[Stage::Trace].items);
  CHECK(st.shade[int(MaterialType::Lambert)].items > 0);
  CHECK(st.shade[int(MaterialType::CoatedDiffuse)].items > 0);
  CHECK(st.shade[int(MaterialType::Dielectric)].items > 0);
  for (const MaterialType t : {MaterialType::OrenNayar, MaterialType::Mirror, MaterialType::Conductor,
                               MaterialType::ThinDielectric}) {
    CHECK(st.shade[int(t)].calls == 0);
    CHECK(st.shade[int(t)].items == 0);
  }
  const bool igi = k == IntegratorKind::Igi;
  CHECK((st[Stage::VplPass].calls > 0) == igi);
  CHECK((st[Stage::VplPass].items > 0) == igi);
  CHECK((st[Stage::VplGather].items > 0) == igi);
  if (igi) CHECK(st[Stage::VplGather].items <= st[Stage::Shadows].items);  // every VPL ray queued is traced

  for (const StageTime& t : st.stage) CHECK(t.seconds >= 0);
  for (const StageTime& t : st.shade) CHECK(t.seconds >= 0);
  CHECK(st[Stage::Trace].seconds > 0);
  CHECK(st.threads >= 1);
  CHECK(st.threads <= 2);
  // Each thread's laps lie within the render, so they sum to at most threads x wall time (with a millisecond for
  // the clock reads of the threads, which are not ordered with the render's own: measured 0.4 % over, under load).
  CHECK(st.total_seconds() > 0);
  CHECK(st.total_seconds() <= double(st.threads) * r.render_seconds + 1e-3);
}

}  // namespace

TEST_CASE("stage profile: counts agree with the render's ray and sample counts", "[render][stats]") {
  const auto scene = three_material_scene();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  for (const IntegratorKind k : {IntegratorKind::Path, IntegratorKind::Direct, IntegratorKind::Igi}) {
    INFO("integrator " << int(k));
    const RenderSettings s = settings(k, true);
    check_consistent(render_view(*scene, kCamera, s).stats, k, s);
  }
}

TEST_CASE("stage profile: off by default, and collecting it leaves the image bitwise unchanged", "[render][stats]") {
  const auto scene = three_material_scene();
  for (const IntegratorKind k : {IntegratorKind::Path, IntegratorKind::Igi}) {
    INFO("integrator " << int(k));
    const RenderOutput off = render_view(*scene, kCamera, settings(k, false));
    const RenderOutput on = render_view(*scene, kCamera, settings(k, true));
    CHECK_FALSE(off.stats.stages.enabled);
    CHECK(off.stats.stages.total_seconds() == 0);
    for (const StageTime& t : off.stats.stages.stage) CHECK(t.calls == 0);
    for (const StageTime& t : off.stats.stages.shade) CHECK(t.calls == 0);
    CHECK(on.stats.rays() == off.stats.rays());
    REQUIRE(on.image.pixels.size() == off.image.pixels.size());
    CHECK(std::memcmp(on.image.pixels.data(), off.image.pixels.data(), on.image.pixels.size() * sizeof(Rgb)) == 0);
  }
}

TEST_CASE("stage profile: the table has a line per stage and per material type shaded", "[render][stats]") {
  StageStats st;
  st.enabled = true;
  st.threads = 2;
  for (int i = 0; i < kStageCount; ++i) st.stage[i] = {0.25, 3, 100};
  st.stage[int(Stage::VplPass)] = {};  // not an IGI render: no VPL lines
  st.stage[int(Stage::VplGather)] = {};
  st.stage[int(Stage::Connect)] = {};  // nor a BDPT render
  st.stage[int(Stage::Trace)].items = 1000000;
  st.shade[int(MaterialType::Lambert)] = {0.5, 2, 40};
  st.shade[int(MaterialType::CoatedDiffuse)] = {0.25, 2, 10};
  const std::string table = format_stage_table(st, 1.0);
  for (const char* line : {"camera ", "trace ", "hits ", "emission ", "shade lambert ", "shade plastic ", "shadows ",
                           "film ", "total "})
    CHECK_THAT(table, Catch::Contains(std::string("  ") + line));
  CHECK_THAT(table, !Catch::Contains("vpl_"));
  CHECK_THAT(table, !Catch::Contains("shade glass"));
  CHECK_THAT(table, Catch::Contains("4.00 Mrays/s per thread"));  // trace: 1 M rays in 0.25 s
  CHECK_THAT(table, Catch::Contains("2.2500 s of 2 threads x 1.000 s wall (112.5 %"));
  st.stage[int(Stage::VplPass)] = {0.1, 4, 50};
  CHECK_THAT(format_stage_table(st, 1.0), Catch::Contains("  vpl_pass "));
}
