// The many-light sampler (light/light_bvh.h): cone unions hold both cones, the probabilities of all lights sum to
// one at any receiver, sampling frequencies follow them (chi-square), lights that cannot reach a point are never
// chosen while those that can always may be, and lights at infinity keep their fixed share.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <memory>
#include <string>

#include "chi2.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "hwy_targets.h"
#include "light/emissive_patches.h"
#include "light/light_bvh.h"
#include "simd/light_bvh_batch.h"

using namespace torte;
using namespace torte::test;

namespace {

Vec3f random_dir(Pcg32& rng) { return sample_uniform_sphere({rng.next_float(), rng.next_float()}); }

// A unit-ish square emitter at `c` whose front faces `n` (winding), as a scene mesh.
TriangleMesh quad(Vec3f c, Vec3f n, float size) {
  const Frame f = Frame::from_z(normalize(n));
  TriangleMesh m;
  for (const auto [a, b] : {std::pair{-1, -1}, std::pair{1, -1}, std::pair{1, 1}, std::pair{-1, 1}})
    m.add_vertex(c + f.s * (float(a) * size) + f.t * (float(b) * size));
  m.add_triangle(0, 1, 2);
  m.add_triangle(0, 2, 3);
  return m;
}

struct TestScene {
  std::vector<TriangleMesh> meshes;
  std::vector<Light> lights;
  std::vector<float> power;
  EmitterView view() const { return {meshes, {}, {}, {0, 0, 0}, 20}; }
};

// Many small one-sided quads, points and spots scattered in a 20-unit cube, plus `infinite` lights at infinity
// (directional).
TestScene make_scene(int quads, int points, int spots, int infinite, uint64_t seed) {
  TestScene s;
  Pcg32 rng(seed);
  const auto pos = [&] { return Vec3f(rng.next_float() * 20 - 10, rng.next_float() * 20 - 10, rng.next_float() * 20 - 10); };
  for (int i = 0; i < quads; ++i) {
    s.meshes.push_back(quad(pos(), random_dir(rng), 0.1f + rng.next_float()));
    Light l;
    l.kind = LightKind::Area;
    l.object = uint32_t(i);
    l.radiance = Rgb(0.5f + 4 * rng.next_float());
    REQUIRE(prepare_mesh_light(s.meshes.back(), &l));  // as Scene sets it up for sample_light
    l.two_sided = i % 5 == 0;
    s.lights.push_back(l);
  }
  for (int i = 0; i < points + spots; ++i) {
    Light l;
    l.kind = i < points ? LightKind::Point : LightKind::Spot;
    l.position = pos();
    l.radiance = Rgb(0.2f + rng.next_float());
    l.direction = random_dir(rng);
    l.cos_total = std::cos(0.3f + rng.next_float());
    l.cos_falloff_start = std::min(1.0f, l.cos_total + 0.05f);
    s.lights.push_back(l);
  }
  // Directional lights: uniform infinite lights are left to BSDF sampling and never reach the sampler. Irradiance
  // pi, what a uniform sky of radiance 1 gives.
  for (int i = 0; i < infinite; ++i) {
    Light l;
    l.kind = LightKind::Distant;
    l.direction = random_dir(rng);
    l.radiance = Rgb(kPi);
    s.lights.push_back(l);
  }
  for (const Light& l : s.lights) s.power.push_back(light_power(s.view(), l));
  return s;
}

// Whether any point of light l can send light to p (exactly, by the light's own geometry).
bool reaches(const TestScene& s, const Light& l, Vec3f p) {
  if (l.kind == LightKind::Point) return true;
  if (l.kind == LightKind::Spot) return dot(normalize(p - l.position), l.direction) > l.cos_total;
  if (l.kind != LightKind::Area) return true;
  const TriangleMesh& m = s.meshes[l.object];
  const Vec3f p0 = m.position(0), n = normalize(cross(m.position(1) - p0, m.position(2) - p0));
  return l.two_sided || dot(p - p0, n) > 0;
}

// A one-sided quad that p lies clearly behind: more than 30 degrees behind its plane and further away than twice
// its size, so that even the quad's bounding box, as the sampler sees it, faces away from p.
bool clearly_behind(const TestScene& s, const Light& l, Vec3f p) {
  if (l.kind != LightKind::Area || l.two_sided) return false;
  const TriangleMesh& m = s.meshes[l.object];
  Vec3f c{0, 0, 0};
  for (uint32_t i = 0; i < 4; ++i) c = c + m.position(i) * 0.25f;
  const Vec3f n = normalize(cross(m.position(1) - m.position(0), m.position(2) - m.position(0)));
  const float size = length(m.position(2) - m.position(0));
  return dot(normalize(p - c), n) < -0.5f && length(p - c) > 2 * size;
}

// Adds to s a Patches light of `count` random patches in the same cube: one-sided parallelograms and, every fourth,
// a two-sided triangle (a voxel grid's emitting faces and cell shapes).
std::shared_ptr<EmissivePatches> add_patches(TestScene& s, int count, uint64_t seed) {
  auto patches = std::make_shared<EmissivePatches>();
  Pcg32 rng(seed);
  for (int i = 0; i < count; ++i) {
    const Vec3f o(rng.next_float() * 20 - 10, rng.next_float() * 20 - 10, rng.next_float() * 20 - 10);
    const Frame f = Frame::from_z(random_dir(rng));
    const Rgb L(0.2f + 2 * rng.next_float());
    if (i % 4 == 3) patches->add_triangle(o, o + f.s * 0.5f, o + f.t * 0.5f, L, true);
    else patches->add_parallelogram(o, f.s * 0.4f, f.t * 0.3f, f.n, L, false);
  }
  patches->finish();
  Light pl;
  pl.kind = LightKind::Patches;
  pl.patches = patches;
  s.lights.push_back(pl);
  s.power.push_back(light_power(s.view(), pl));
  return patches;
}

}  // namespace

TEST_CASE("light bvh: the union of two cones holds both", "[lights][light_bvh]") {
  Pcg32 rng(3);
  for (int t = 0; t < 2000; ++t) {
    const DirectionCone a{random_dir(rng), std::cos(rng.next_float() * kPi), false};
    const DirectionCone b{random_dir(rng), std::cos(rng.next_float() * kPi), false};
    const DirectionCone m = merge(a, b);
    for (int k = 0; k < 8; ++k) {
      const DirectionCone& c = k % 2 ? a : b;
      // A direction on the rim of c, which must lie in m.
      const Frame f = Frame::from_z(c.w);
      const float phi = rng.next_float() * 2 * kPi, sin_t = std::sqrt(std::max(0.0f, 1 - c.cos_theta * c.cos_theta));
      const Vec3f d = f.to_world({sin_t * std::cos(phi), sin_t * std::sin(phi), c.cos_theta});
      INFO("trial " << t);
      REQUIRE(dot(m.w, d) >= m.cos_theta - 2e-4f);
    }
  }
}

TEST_CASE("light bvh: sampling follows the probabilities, and lights facing away are never chosen",
          "[lights][light_bvh]") {
  const TestScene s = make_scene(60, 20, 20, 0, 11);
  const LightBvh bvh(s.view(), s.lights, s.power);
  REQUIRE_FALSE(bvh.empty());
  Pcg32 rng(5);
  for (int trial = 0; trial < 6; ++trial) {
    const Vec3f p(rng.next_float() * 24 - 12, rng.next_float() * 24 - 12, rng.next_float() * 24 - 12);
    const Vec3f n = trial % 2 ? random_dir(rng) : Vec3f(0, 0, 0);
    INFO("receiver " << p.x << " " << p.y << " " << p.z << " normal " << n.x << " " << n.y << " " << n.z);
    // Bin per light plus one for "no light": the bounds are conservative, so the descent may reach a leaf that
    // cannot light p and return none; that probability is what the lights' sum lacks of 1.
    double sum = 0;
    std::vector<double> expected(s.lights.size() + 1);
    for (size_t l = 0; l < s.lights.size(); ++l) {
      const float pmf = bvh.pmf(p, n, int(l));
      sum += pmf;
      expected[l] = pmf;
      if (clearly_behind(s, s.lights[l], p)) {
        INFO("light " << l << " faces away from the receiver");
        CHECK(pmf == 0);
      }
    }
    CHECK(sum <= 1 + 1e-5);
    CHECK(sum > 0.5);
    expected.back() = std::max(0.0, 1 - sum);
    constexpr int kSamples = 200000;
    std::vector<double> observed(s.lights.size() + 1);
    for (int k = 0; k < kSamples; ++k) {
      float pmf = 0;
      uint32_t part = 0;
      const int l = bvh.sample(p, n, rng.next_float(), &pmf, &part);
      REQUIRE(part == 0);
      if (l < 0) {
        REQUIRE(pmf == 0);
        observed.back() += 1;
        continue;
      }
      REQUIRE(pmf == Approx(bvh.pmf(p, n, l)).epsilon(1e-4));
      observed[size_t(l)] += 1;
    }
    for (double& e : expected) e *= kSamples;
    const Chi2Result r = chi2_test(observed, expected, 0.01, 6);
    INFO(r.message);
    CHECK(r.passed);
  }
}

TEST_CASE("light bvh: a group emitting everywhere weighs the receiver by cos(max(0, theta_i - theta_b)), as a cone would",
          "[lights][light_bvh]") {
  // Spheres' and points' groups take a shortcut through the cosines scaled by the distance; here against the
  // angles themselves: theta_i between the receiver normal and the box centre, theta_b the box's bounding sphere.
  Pcg32 rng(5);
  int bounded = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    LightBounds b;
    const Vec3f lo(rng.next_float() * 4 - 2, rng.next_float() * 4 - 2, rng.next_float() * 4 - 2);
    b.bounds.extend(lo);
    b.bounds.extend(lo + Vec3f(rng.next_float(), rng.next_float(), rng.next_float()) * 2.0f);
    b.phi = 0.5f + rng.next_float();
    b.normals = DirectionCone::everywhere();
    b.cos_theta_e = std::cos(kPi / 2);
    const Vec3f p(rng.next_float() * 12 - 6, rng.next_float() * 12 - 6, rng.next_float() * 12 - 6);
    const Vec3f n = random_dir(rng);
    const Vec3f c = b.bounds.center();
    const float dc2 = length_squared(p - c), r2 = length_squared(b.bounds.diagonal()) / 4;
    const float d2 = std::max(dc2, length_squared(b.bounds.diagonal()) / 64);
    float expected = b.phi / d2;
    if (dc2 > r2) {
      const float theta_i = std::acos(std::min(1.0f, std::fabs(dot(p - c, n)) / std::sqrt(dc2)));
      const float theta_b = std::asin(std::sqrt(r2 / dc2));
      expected *= std::cos(std::max(0.0f, theta_i - theta_b));
      bounded += theta_i > theta_b;
    }
    INFO("trial " << trial);
    CHECK(b.importance(p, n) == Approx(expected).epsilon(2e-3).margin(1e-6));
    CHECK(b.importance(p, {0, 0, 0}) == Approx(b.phi / d2).epsilon(1e-5));
  }
  CHECK(bounded > 500);  // most trials exercise the bound, not only the points near or facing the box
}

TEST_CASE("light bvh: a light that can reach the receiver is never given probability zero", "[lights][light_bvh]") {
  const TestScene s = make_scene(200, 30, 30, 0, 29);
  const LightBvh bvh(s.view(), s.lights, s.power);
  Pcg32 rng(8);
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3f p(rng.next_float() * 30 - 15, rng.next_float() * 30 - 15, rng.next_float() * 30 - 15);
    for (size_t l = 0; l < s.lights.size(); ++l)
      if (reaches(s, s.lights[l], p)) {
        INFO("trial " << trial << " light " << l);
        REQUIRE(bvh.pmf(p, {0, 0, 0}, int(l)) > 0);
      }
  }
}

TEST_CASE("light bvh: lights at infinity share a probability weighed by irradiance; only they when nothing is bounded",
          "[lights][light_bvh]") {
  const TestScene s = make_scene(10, 0, 0, 2, 4);
  const LightBvh bvh(s.view(), s.lights, s.power);
  const Vec3f p(0.5f, 0.25f, 0);
  const float p_inf = bvh.infinite_probability(p, {0, 0, 0});
  CHECK(p_inf >= LightBvh::kMinShare);
  CHECK(p_inf <= 1 - LightBvh::kMinShare);
  CHECK(bvh.pmf(p, {0, 0, 0}, 10) == Approx(p_inf / 2));  // uniformly among the lights at infinity
  CHECK(bvh.pmf(p, {0, 0, 0}, 11) == Approx(p_inf / 2));
  double bounded = 0;
  for (int l = 0; l < 10; ++l) bounded += bvh.pmf(p, {0, 0, 0}, l);
  CHECK(bounded == Approx(1 - p_inf).epsilon(1e-4));
  // A faint sky gets less than the bounded lights near p, more far from them, and a bright one more.
  TestScene faint = s;
  for (size_t l = 10; l < 12; ++l) faint.power[l] *= 1e-4f;
  const LightBvh faint_bvh(faint.view(), faint.lights, faint.power);
  const float near_share = faint_bvh.infinite_probability(p, {0, 0, 0});
  INFO("sky share: " << p_inf << ", faint sky near the lights " << near_share << ", far from them "
                     << faint_bvh.infinite_probability({0, 3000, 0}, {0, 0, 0}));
  CHECK(near_share < p_inf);
  CHECK(near_share >= LightBvh::kMinShare);
  CHECK(faint_bvh.infinite_probability({0, 3000, 0}, {0, 0, 0}) > near_share);

  const TestScene sky_only = make_scene(0, 0, 0, 1, 4);
  const LightBvh only(sky_only.view(), sky_only.lights, sky_only.power);
  float pmf = 0;
  uint32_t part = 7;
  CHECK(only.sample(p, {0, 0, 0}, 0.7f, &pmf, &part) == 0);
  CHECK(part == 0);
  CHECK(pmf == 1);
  CHECK(only.pmf(p, {0, 0, 0}, 0) == 1);
  CHECK(LightBvh().empty());

  // A uniform infinite light is left to BSDF sampling: never chosen, pmf 0, no share taken from the others.
  TestScene with_uniform = make_scene(10, 0, 0, 0, 4);
  Light uniform;
  uniform.kind = LightKind::Infinite;
  uniform.radiance = Rgb(1);
  with_uniform.lights.push_back(uniform);
  with_uniform.power.push_back(light_power(with_uniform.view(), uniform));
  const LightBvh u_bvh(with_uniform.view(), with_uniform.lights, with_uniform.power);
  CHECK(u_bvh.infinite_probability(p, {0, 0, 0}) == 0);
  CHECK(u_bvh.pmf(p, {0, 0, 0}, 10) == 0);
  for (int k = 0; k < 64; ++k) CHECK(u_bvh.sample(p, {0, 0, 0}, (k + 0.5f) / 64, &pmf, &part) != 10);
  const TestScene uniform_only{{}, {uniform}, {light_power(TestScene{}.view(), uniform)}};
  const LightBvh u_only(uniform_only.view(), uniform_only.lights, uniform_only.power);
  CHECK(u_only.sample(p, {0, 0, 0}, 0.5f, &pmf, &part) == -1);
  CHECK(u_only.pmf(p, {0, 0, 0}, 0) == 0);
}

TEST_CASE("light bvh: the parts of a Patches light are leaves; their probabilities follow sampling",
          "[lights][light_bvh][voxel]") {
  TestScene s = make_scene(20, 5, 5, 1, 17);
  const std::shared_ptr<EmissivePatches> patches = add_patches(s, 150, 21);
  Pcg32 rng(22);
  const int li = int(s.lights.size() - 1);
  const LightBvh bvh(s.view(), s.lights, s.power);
  // Bins: one per light but the Patches light, one per part of it, one for "no light".
  const size_t parts = patches->part_count(), bins = size_t(li) + parts + 1;
  const auto bin = [&](int l, uint32_t part) { return l == li ? size_t(li) + part : size_t(l); };
  for (int trial = 0; trial < 4; ++trial) {
    const Vec3f p(rng.next_float() * 20 - 10, rng.next_float() * 20 - 10, rng.next_float() * 20 - 10);
    const Vec3f n = trial % 2 ? random_dir(rng) : Vec3f(0, 0, 0);
    INFO("receiver " << p.x << " " << p.y << " " << p.z);
    std::vector<double> expected(bins), observed(bins);
    double sum = 0;
    for (int l = 0; l < li; ++l) sum += expected[bin(l, 0)] = bvh.pmf(p, n, l);
    for (uint32_t j = 0; j < parts; ++j) {
      sum += expected[bin(li, j)] = bvh.pmf(p, n, li, j);
      const EmissivePatch& q = patches->patch(j);
      // A patch p lies in front of (or any two-sided one) can light it: never probability zero.
      if (n.x == 0 && n.y == 0 && n.z == 0 && (q.two_sided || dot(p - q.p, q.n) > 1e-3f)) CHECK(expected[bin(li, j)] > 0);
    }
    CHECK(bvh.pmf(p, n, li, uint32_t(parts)) == 0);
    CHECK(sum <= 1 + 1e-5);
    CHECK(sum > 0.5);
    expected.back() = std::max(0.0, 1 - sum);
    constexpr int kSamples = 200000;
    for (int k = 0; k < kSamples; ++k) {
      float pmf = 0;
      uint32_t part = 0;
      const int l = bvh.sample(p, n, rng.next_float(), &pmf, &part);
      if (l < 0) {
        observed.back() += 1;
        continue;
      }
      if (l != li) REQUIRE(part == 0);
      REQUIRE(pmf == Approx(bvh.pmf(p, n, l, part)).epsilon(1e-4));
      observed[bin(l, part)] += 1;
    }
    for (double& e : expected) e *= kSamples;
    const Chi2Result r = chi2_test(observed, expected, 0.01, 4);
    INFO(r.message);
    CHECK(r.passed);
  }
}

TEST_CASE("light bvh: weighed by visibility, the lights at infinity get more where the bounded lights are hidden",
          "[lights][light_bvh]") {
  const TestScene s = make_scene(40, 10, 0, 1, 31);
  LightBvh open(s.view(), s.lights, s.power), weighed(s.view(), s.lights, s.power);
  // Rays towards bounded lights (finite length) from x > 0 are blocked; the sky is seen from everywhere.
  weighed.weigh_visibility(s.view(), s.lights, [](const Ray& r) { return r.t_max < kInfinity && r.o.x > 0; });
  Pcg32 rng(4);
  int more = 0, same = 0, trials = 0;
  for (int t = 0; t < 400; ++t) {
    const Vec3f p(rng.next_float() * 20 - 10, rng.next_float() * 20 - 10, rng.next_float() * 20 - 10);
    if (std::fabs(p.x) < 2) continue;  // cells across x = 0 see both
    ++trials;
    const float a = open.infinite_probability(p, {0, 0, 0}), b = weighed.infinite_probability(p, {0, 0, 0});
    INFO("p " << p.x << " " << p.y << " " << p.z << ": " << a << " -> " << b);
    if (p.x > 0) {
      CHECK(b >= a);
      more += b > a;
    } else {
      CHECK(b == Approx(a).epsilon(1e-5));
      same += 1;
    }
    // Sampling and pmf agree with the weighed share.
    float pmf = 0;
    uint32_t part = 0;
    const int l = weighed.sample(p, {0, 0, 0}, 0.5f * b, &pmf, &part);
    CHECK(l == int(s.lights.size()) - 1);
    CHECK(pmf == Approx(b));
  }
  CHECK(more > trials / 4);
  CHECK(same > trials / 4);
}

TEST_CASE("light bvh: the batch descent gives sample()'s lights, parts and probabilities bit for bit on every target",
          "[lights][light_bvh][simd]") {
  // Quads (cones of normals, some two-sided), points (normals everywhere), spots (emission cones), a Patches light's
  // parts and directional lights at infinity; receivers with and without normals, some next to the lights.
  TestScene s = make_scene(40, 30, 10, 2, 41);
  add_patches(s, 60, 43);
  Pcg32 rng(44);
  const LightBvh bvh(s.view(), s.lights, s.power);
  // Counts around the vector widths exercise the padded remainder.
  for (const size_t count : {size_t(1), size_t(7), size_t(16), size_t(1001)}) {
    std::vector<Vec3f> p(count), n(count);
    std::vector<float> u(count);
    for (size_t k = 0; k < count; ++k) {
      p[k] = k % 4 == 0 ? s.lights[k % s.lights.size()].position + random_dir(rng) * 0.01f
                        : Vec3f(rng.next_float() * 24 - 12, rng.next_float() * 24 - 12, rng.next_float() * 24 - 12);
      n[k] = k % 3 == 0 ? Vec3f(0, 0, 0) : random_dir(rng);
      u[k] = k % 11 == 0 ? 0x1.fffffep-1f : rng.next_float();
    }
    test::for_each_hwy_target(&light_bvh_batch_target_name, [&](const std::string&) {
      std::vector<int> light(count, -7);
      std::vector<float> pmf(count, -1);
      std::vector<uint32_t> part(count, 99);
      bvh.sample_batch(count, p.data(), n.data(), u.data(), light.data(), pmf.data(), part.data());
      for (size_t k = 0; k < count; ++k) {
        float expected_pmf = -1;
        uint32_t expected_part = 99;
        const int expected = bvh.sample(p[k], n[k], u[k], &expected_pmf, &expected_part);
        INFO("count " << count << " receiver " << k);
        REQUIRE(light[k] == expected);
        REQUIRE(part[k] == expected_part);
        REQUIRE(std::bit_cast<uint32_t>(pmf[k]) == std::bit_cast<uint32_t>(expected_pmf));
      }
    });
  }
}
