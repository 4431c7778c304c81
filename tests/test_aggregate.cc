// The aggregate's batched instance level (accel/instance_level.cc) against a scalar reference: every ray traced
// alone through the root set and then through every instance's prototype, nearest hit kept. Scenes of many
// instances, with nested groups (composed transforms, mirrors, non-uniform scales), quadrics and voxel grids
// with cell shapes; queues coherent and not, finite and infinite t_max.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <vector>

#include "core/rng.h"
#include "scene/builder.h"
#include "scene/scene.h"
#include "scene_helpers.h"
#include "voxel/voxel_shape.h"
#include "voxel_scene_helpers.h"

using namespace torte;
using namespace torte::test;

namespace {

std::vector<ShapeDesc> mixed_shapes() {
  std::vector<ShapeDesc> shapes;
  shapes.push_back(sphere_shape(0.4f, translate({0.5f, 0.1f, 0}), matte(0.6f)));
  ShapeDesc disk = sphere_shape(0.3f, translate({-0.5f, 0, 0.2f}) * rotate(50, {1, 0, 0}), matte(0.5f));
  disk.quadric.kind = QuadricKind::Disk;
  shapes.push_back(disk);
  ShapeDesc cube;
  cube.kind = ShapeDesc::Kind::Mesh;
  cube.mesh = std::make_shared<TriangleMesh>(make_cube());
  cube.transform = translate({0, -0.3f, 0.4f}) * rotate(20, {0, 1, 1}) * scale({0.3f, 0.2f, 0.35f});
  cube.material = matte(0.4f);
  shapes.push_back(cube);
  return shapes;
}

// A 6^3 grid of cubes with holes and slab cells (id -1, a cube mesh in the cell).
std::shared_ptr<VoxelShape> small_world() {
  VoxelGrid g;
  for (int z = 0; z < 6; ++z)
    for (int x = 0; x < 6; ++x)
      for (int y = 0; y < 1 + (x * 3 + z) % 4; ++y)
        if ((x + y + z) % 3 != 0) g.set(x, y, z, int16_t((x + z) % 5 == 0 ? -1 : 1 + (y % 2)));
  return slab_world(g, matte(0.3f));
}

// Root shapes, ~100 instances of a mixed group, nested groups holding it and a voxel grid, and grids alone.
std::shared_ptr<Scene> many_instances() {
  auto mixed = std::make_shared<SceneBuilder>();
  for (const ShapeDesc& s : mixed_shapes()) mixed->add_shape(s);
  auto grid = std::make_shared<SceneBuilder>();
  grid->add_shape(voxel_desc(small_world(), scale({0.15f, 0.15f, 0.15f})));
  auto nested = std::make_shared<SceneBuilder>();
  nested->add_instance({mixed, translate({0.4f, 0, 0}) * scale({0.5f, 0.7f, 0.5f})});
  nested->add_instance({mixed, translate({-0.4f, 0.3f, 0}) * scale({-0.6f, 0.5f, 0.5f}) * rotate(30, {0, 0, 1})});
  nested->add_instance({grid, translate({0, -0.5f, -0.3f}) * rotate(15, {1, 1, 0})});
  nested->add_shape(sphere_shape(0.15f, translate({0, 0.6f, 0}), matte(0.2f)));
  auto outer = std::make_shared<SceneBuilder>();  // nesting two deep
  outer->add_instance({nested, rotate(40, {0, 1, 0})});
  outer->add_instance({nested, translate({0.8f, 0.2f, 0.1f}) * scale({0.5f, 0.5f, 0.5f})});

  SceneBuilder b;
  for (const ShapeDesc& s : mixed_shapes()) {
    ShapeDesc root = s;
    root.transform = translate({0, -2.5f, 1}) * scale({3, 1, 3}) * s.transform;
    b.add_shape(root);
  }
  Pcg32 rng(3);
  const auto jitter = [&] { return rng.next_float() * 2 - 1; };
  for (int i = 0; i < 96; ++i) {
    const Vec3f at(-4 + 8 * rng.next_float(), -2 + 4 * rng.next_float(), -1 + 4 * rng.next_float());
    const Transform t = translate(at) * rotate(180 * jitter(), {jitter(), jitter(), 0.5f}) *
                        scale({0.4f + 0.5f * rng.next_float(), (i % 7 == 0 ? -1.0f : 1.0f) * (0.4f + 0.5f * rng.next_float()),
                               0.4f + 0.5f * rng.next_float()});
    const int kind = i % 4;
    b.add_instance({kind == 3 ? grid : kind == 2 ? outer : kind == 1 ? nested : mixed, t});
  }
  return b.flatten();
}

// The scalar reference: one ray at a time, every instance tried, strictly closer hits kept.
Hit reference_hit(const Scene& scene, const Ray& ray) {
  Hit h;
  scene.accel().root().intersect_one(ray, &h);
  for (uint32_t k = 0; k < scene.instances.size(); ++k) {
    const Instance& inst = scene.instances[k];
    Hit c = h;
    c.instance = k;
    if (scene.prototypes[inst.prototype]->geometry.intersect_one(inst.to_world.apply_inverse(ray), &c)) h = c;
  }
  return h;
}

bool reference_occluded(const Scene& scene, const Ray& ray) {
  if (scene.accel().root().occluded_one(ray)) return true;
  for (const Instance& inst : scene.instances)
    if (scene.prototypes[inst.prototype]->geometry.occluded_one(inst.to_world.apply_inverse(ray))) return true;
  return false;
}

struct Queue {
  std::vector<float> v[7];
  void push(const Ray& r) {
    const float f[7] = {r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.t_max};
    for (int k = 0; k < 7; ++k) v[k].push_back(f[k]);
  }
  size_t size() const { return v[0].size(); }
  RaySoA soa() const { return {v[0].data(), v[1].data(), v[2].data(), v[3].data(), v[4].data(), v[5].data(), v[6].data()}; }
};

// Incoherent rays from all around, or (coherent) groups of 8 neighbours from one eye, a quarter with finite t_max.
Queue make_queue(bool coherent, int n, uint64_t seed) {
  Pcg32 rng(seed);
  Queue q;
  Vec3f eye;
  for (int i = 0; i < n; ++i) {
    if (!coherent || i % 64 == 0)
      eye = Vec3f(-7 + 14 * rng.next_float(), -5 + 10 * rng.next_float(), -8 + 4 * rng.next_float());
    const Vec3f target(-4 + 8 * rng.next_float(), -2.5f + 5 * rng.next_float(), -1 + 4 * rng.next_float());
    const float t_max = i % 4 == 0 ? 2 + 10 * rng.next_float() : kInfinity;
    q.push(Ray{eye, normalize(target - eye), t_max});
  }
  return q;
}

void check_against_reference(const Scene& scene, bool coherent) {
  const Queue q = make_queue(coherent, 6000, coherent ? 11 : 12);
  const size_t n = q.size();
  std::vector<Hit> hits(n);
  std::vector<uint8_t> blocked(n);
  scene.intersect(q.soa(), n, hits.data(), coherent);
  scene.occluded(q.soa(), n, blocked.data(), coherent);
  int found = 0, in_instances = 0, in_grids = 0, blocked_count = 0;
  for (size_t i = 0; i < n; ++i) {
    const Ray r = ray_at(q.soa(), i);
    const Hit ref = reference_hit(scene, r);
    INFO("ray " << i << (coherent ? " (coherent)" : ""));
    REQUIRE(hits[i].prim == ref.prim);
    REQUIRE(hits[i].instance == ref.instance);
    if (ref.prim != kNoHit) {
      CHECK(hits[i].t == ref.t);
      CHECK(hits[i].b1 == ref.b1);
      CHECK(hits[i].b2 == ref.b2);
      ++found;
      in_instances += ref.instance != kNoHit;
      in_grids += is_voxel_prim(ref.prim) && ref.instance != kNoHit;
    }
    REQUIRE(bool(blocked[i]) == reference_occluded(scene, r));
    blocked_count += blocked[i];
    // The single-ray entry points take the same path.
    Ray one = r;
    Hit h1;
    REQUIRE(scene.intersect(one, &h1) == (ref.prim != kNoHit));
    CHECK(h1.prim == ref.prim);
    CHECK(h1.instance == ref.instance);
    CHECK(scene.occluded(r) == bool(blocked[i]));
  }
  // The rays reach every kind of geometry, and enough of them miss or stay unblocked to test that side too.
  CHECK(found > int(n) / 4);
  CHECK(found < int(n) - int(n) / 20);
  CHECK(in_instances > found / 2);
  CHECK(in_grids > 50);
  CHECK(blocked_count < int(n) - int(n) / 20);
}

}  // namespace

TEST_CASE("batched instance level: same hits and occlusion as the scalar reference", "[instancing][accel]") {
  const auto scene = many_instances();
  REQUIRE(scene->instances.size() > 150);  // nested groups unrolled
  REQUIRE(scene->prototypes.size() == 3);  // `outer` holds instances only: no prototype of its own
  SECTION("incoherent queue") { check_against_reference(*scene, false); }
  SECTION("coherent queue") { check_against_reference(*scene, true); }
}

TEST_CASE("batched instance level: queues of every size, rays out of order, empty and degenerate rays", "[instancing][accel]") {
  const auto scene = many_instances();
  const Queue q = make_queue(false, 700, 5);
  for (size_t count : {size_t(0), size_t(1), size_t(3), size_t(17), size_t(700)}) {
    // A queue in reverse order, with a zero-length and a NaN ray in it: results stay per ray, in queue order.
    Queue r;
    for (size_t i = count; i-- > 0;) r.push(ray_at(q.soa(), i));
    if (count > 2) {
      r.v[6][1] = 0;
      r.v[3][2] = std::nanf("");
    }
    std::vector<Hit> hits(r.size());
    std::vector<uint8_t> blocked(r.size());
    scene->intersect(r.soa(), r.size(), hits.data(), false);
    scene->occluded(r.soa(), r.size(), blocked.data(), false);
    for (size_t i = 0; i < r.size(); ++i) {
      const Hit ref = reference_hit(*scene, ray_at(r.soa(), i));
      INFO("count " << count << " ray " << i);
      CHECK(hits[i].prim == ref.prim);
      CHECK(hits[i].instance == ref.instance);
      CHECK(bool(blocked[i]) == reference_occluded(*scene, ray_at(r.soa(), i)));
      if (count > 2 && (i == 1 || i == 2)) CHECK(hits[i].prim == kNoHit);
      if (count > 2 && i == 1) CHECK(!blocked[i]);  // (a NaN ray's occlusion is whatever the reference says)
    }
  }
}
