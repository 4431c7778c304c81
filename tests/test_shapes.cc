// Ray-shape intersection (triangle, sphere, disk, cylinder), watertightness of closed meshes, surface
// parameterization, area and area sampling of the analytic shapes.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "chi2.h"
#include "core/error.h"
#include "core/rng.h"
#include "core/transform.h"
#include "geometry/quadric.h"
#include "geometry/triangle.h"
#include "test_random.h"

using namespace torte;
using torte::test::random_direction;

namespace {

// translate . rotate . non-uniform scale, and a mirrored variant (negative determinant).
Transform general_transform() {
  return translate({1.5f, -2, 3}) * rotate(37, {1, 2, -0.5f}) * scale({0.7f, 1.9f, 1.3f});
}
Transform mirrored_transform() {
  return translate({-1, 0.5f, 2}) * rotate(-71, {0.3f, -1, 2}) * scale({-1.2f, 0.8f, 2.1f});
}

Quadric make(QuadricKind kind, Transform tf = {}) {
  Quadric q;
  q.kind = kind;
  q.to_world = tf;
  if (kind == QuadricKind::Disk) q.inner_radius = 0.25f;
  if (kind == QuadricKind::Cylinder) q.z_min = -0.5f, q.z_max = 1.5f;
  return q;
}

const QuadricKind kKinds[] = {QuadricKind::Sphere, QuadricKind::Disk, QuadricKind::Cylinder};

float hit_t(const Quadric& q, Ray r, Vec2f* uv = nullptr) {
  float t = -1;
  return intersect(q, r, &t, uv) ? t : -1;
}

// Distance between u coordinates on the circle (u = 0 and u = 1 are the same phi).
float u_distance(float a, float b) {
  const float d = std::fabs(a - b);
  return std::min(d, 1 - d);
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// Triangle

TEST_CASE("triangle: hit distance and barycentrics, both faces", "[triangle]") {
  const Vec3f p0{0, 0, 0}, p1{1, 0, 0}, p2{0, 1, 0};
  TriangleHit h{};
  REQUIRE(intersect_triangle({{0.25f, 0.5f, 1}, {0, 0, -1}}, p0, p1, p2, &h));
  CHECK(h.t == Approx(1));
  CHECK(h.b1 == Approx(0.25f));
  CHECK(h.b2 == Approx(0.5f));
  REQUIRE(intersect_triangle({{0.25f, 0.5f, -2}, {0, 0, 4}}, p0, p1, p2, &h));  // back face, unnormalized d
  CHECK(h.t == Approx(0.5f));
  CHECK(h.b1 == Approx(0.25f));

  // Random rays: the hit point reconstructed from t equals the one from the barycentrics.
  Pcg32 rng(7);
  const Vec3f a{-1, 2, 0.5f}, b{3, 1, -1}, c{0.5f, -2, 2};
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    // Braces: the three draws in this order with every compiler.
    const Vec3f o = Vec3f{rng.next_float(), rng.next_float(), rng.next_float()} * 10 - Vec3f(5, 5, 5);
    const Ray r{o, random_direction(rng)};
    if (!intersect_triangle(r, a, b, c, &h)) continue;
    ++hits;
    CHECK(h.b1 >= 0);
    CHECK(h.b2 >= 0);
    CHECK(h.b1 + h.b2 <= 1.00001f);
    const Vec3f pb = a * (1 - h.b1 - h.b2) + b * h.b1 + c * h.b2;
    CHECK(distance(r.at(h.t), pb) < 1e-4f);
  }
  CHECK(hits > 300);  // about 2.6 % of these rays hit the triangle
}

TEST_CASE("triangle: misses, t range and degenerate input", "[triangle]") {
  const Vec3f p0{0, 0, 0}, p1{1, 0, 0}, p2{0, 1, 0};
  TriangleHit h{};
  CHECK_FALSE(intersect_triangle({{0.6f, 0.6f, 1}, {0, 0, -1}}, p0, p1, p2, &h));    // beyond the hypotenuse
  CHECK_FALSE(intersect_triangle({{-0.1f, 0.5f, 1}, {0, 0, -1}}, p0, p1, p2, &h));   // left of the edge x = 0
  CHECK_FALSE(intersect_triangle({{0.2f, 0.2f, 1}, {0, 0, 1}}, p0, p1, p2, &h));     // triangle behind
  CHECK_FALSE(intersect_triangle({{0.2f, 0.2f, 0}, {0, 0, 1}}, p0, p1, p2, &h));     // starts on it: t = 0
  CHECK_FALSE(intersect_triangle({{-1, 0.2f, 0}, {1, 0, 0}}, p0, p1, p2, &h));       // in its plane
  CHECK_FALSE(intersect_triangle({{0.2f, 0.2f, 1}, {0, 0, 0}}, p0, p1, p2, &h));     // zero direction
  // t_max is exclusive.
  CHECK_FALSE(intersect_triangle({{0.2f, 0.2f, 1}, {0, 0, -1}, 1.0f}, p0, p1, p2, &h));
  CHECK(intersect_triangle({{0.2f, 0.2f, 1}, {0, 0, -1}, 1.0001f}, p0, p1, p2, &h));
  // Degenerate triangles (collinear, coincident vertices) are never hit.
  CHECK_FALSE(intersect_triangle({{0.5f, 0, 1}, {0, 0, -1}}, p0, p1, {2, 0, 0}, &h));
  CHECK_FALSE(intersect_triangle({{0, 0, 1}, {0, 0, -1}}, p0, p0, p0, &h));
}

TEST_CASE("triangle: an edge function that rounds to zero in float is decided in double", "[triangle]") {
  // Edge B-C passes 1e-14 beside the ray (along +z through the origin): in float both products of the edge
  // function round to 1, exactly they are 1 and 1 - 2^-46. Of the two triangles sharing the edge, only the
  // one on the ray's side may be hit; a float-only test would report both.
  const float e = 0x1p-23f;
  const Vec3f b{1, 1 + e, 1}, c{-(1 - e), -1, 1};
  const Ray r{{0, 0, 0}, {0, 0, 1}};
  TriangleHit h{};
  CHECK(intersect_triangle(r, {-1, 1, 1}, b, c, &h));
  CHECK(h.t == 1);
  CHECK_FALSE(intersect_triangle(r, {1, -1, 1}, b, c, &h));
}

namespace {

struct Mesh {
  std::vector<Vec3f> v;
  std::vector<std::array<int, 3>> f;
};

// Icosahedron subdivided `levels` times with shared vertices, projected onto the unit sphere, then placed by
// a non-uniform transform so vertex coordinates are not round numbers.
Mesh icosphere(int levels, const Transform& tf) {
  const float t = (1 + std::sqrt(5.0f)) / 2;
  Mesh m;
  m.v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6},
         {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10},
         {8, 6, 7}, {9, 8, 1}};
  for (Vec3f& p : m.v) p = normalize(p);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.v.push_back(normalize(m.v[a] + m.v[b]));
      return mid[key] = int(m.v.size()) - 1;
    };
    std::vector<std::array<int, 3>> f;
    for (auto [a, b, c] : m.f) {
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      f.insert(f.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    m.f = std::move(f);
  }
  for (Vec3f& p : m.v) p = tf.apply_point(p);
  return m;
}

Mesh cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.v.push_back({(i & 1) ? 1.f : -1.f, (i & 2) ? 1.f : -1.f, (i & 4) ? 1.f : -1.f});
  m.f = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
         {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

// Number of rays from o towards the targets that hit no triangle of the closed mesh.
int count_leaks(const Mesh& m, Vec3f o, const std::vector<Vec3f>& targets) {
  int leaks = 0;
  for (Vec3f target : targets) {
    const Ray r{o, target - o};
    bool hit = false;
    for (auto [a, b, c] : m.f)
      if (intersect_triangle(r, m.v[a], m.v[b], m.v[c], nullptr)) { hit = true; break; }
    leaks += !hit;
  }
  return leaks;
}

// Ray targets exactly at every vertex, at points on every edge, and in random directions.
std::vector<Vec3f> targets_for(const Mesh& m, Vec3f o, Pcg32& rng) {
  std::vector<Vec3f> t = m.v;
  for (auto [a, b, c] : m.f)
    for (auto [i, j] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
      t.push_back((m.v[i] + m.v[j]) * 0.5f);
      const float s = rng.next_float();
      t.push_back(m.v[i] * s + m.v[j] * (1 - s));
    }
  for (int i = 0; i < 500; ++i) t.push_back(o + random_direction(rng));
  return t;
}

}  // namespace

TEST_CASE("triangle: closed meshes are watertight through shared vertices and edges", "[triangle]") {
  Pcg32 rng(3);
  const Transform tf = translate({0.3f, -0.7f, 1.1f}) * rotate(23, {1, 1, 0.2f}) * scale({1.3f, 0.9f, 2.2f});
  const Mesh ico = icosphere(2, tf);
  REQUIRE(ico.f.size() == 320);
  for (int i = 0; i < 6; ++i) {
    const Vec3f local = Vec3f(rng.next_float(), rng.next_float(), rng.next_float()) * 0.8f - Vec3f(0.4f, 0.4f, 0.4f);
    const Vec3f o = i == 0 ? tf.apply_point({0, 0, 0}) : tf.apply_point(local);
    CHECK(count_leaks(ico, o, targets_for(ico, o, rng)) == 0);
  }
  // The cube: axis-aligned and diagonal rays from its centre hit vertices, edges and the face diagonals exactly.
  const Mesh box = cube();
  for (Vec3f o : {Vec3f(0, 0, 0), Vec3f(0.5f, 0, 0), Vec3f(0.25f, -0.5f, 0.125f)}) {
    std::vector<Vec3f> t = targets_for(box, o, rng);
    for (float x : {-1.f, 0.f, 1.f})
      for (float y : {-1.f, 0.f, 1.f})
        for (float z : {-1.f, 0.f, 1.f})
          if (x != 0 || y != 0 || z != 0) t.push_back(o + Vec3f(x, y, z));
    CHECK(count_leaks(box, o, t) == 0);
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Quadrics under the identity

TEST_CASE("sphere: hits, misses, grazing, inside, t_max", "[quadric]") {
  Quadric q = make(QuadricKind::Sphere);
  q.radius = 2;
  Vec2f uv;
  CHECK(hit_t(q, {{0, 0, -5}, {0, 0, 1}}, &uv) == Approx(3));
  CHECK(uv.y == Approx(1));  // theta = pi at the -z pole
  CHECK(hit_t(q, {{0, 0, -5}, {0, 0, 0.5f}}) == Approx(6));  // t is in units of the unnormalized direction
  CHECK(hit_t(q, {{-5, 0, 0}, {1, 0, 0}}, &uv) == Approx(3));
  CHECK(uv.x == Approx(0.5f));
  CHECK(uv.y == Approx(0.5f));
  CHECK(hit_t(q, {{0, 0, 0}, {0, 1, 0}}, &uv) == Approx(2));  // from inside: the far side
  CHECK(uv.x == Approx(0.25f));
  CHECK(hit_t(q, {{0, 0, 5}, {0, 0, 1}}) < 0);                 // sphere behind the ray
  CHECK(hit_t(q, {{0, 2.001f, -5}, {0, 0, 1}}) < 0);           // passes just outside
  CHECK(hit_t(q, {{0, 1.999f, -5}, {0, 0, 1}}) > 0);           // grazes just inside
  CHECK(hit_t(q, {{0, 0, -5}, {0, 0, 1}, 3.0f}) < 0);          // t_max is exclusive
  CHECK(hit_t(q, {{0, 0, -5}, {0, 0, 1}, 3.001f}) == Approx(3));
  CHECK(hit_t(q, {{0, 0, -2}, {0, 0, -1}}) < 0);               // on the surface, leaving
  CHECK(hit_t(q, {{0, 0, -2}, {0, 0, 1}}) == Approx(4));       // on the surface, entering: far side
  // A far-away origin keeps its precision (the discriminant form does not cancel).
  CHECK(hit_t(q, {{0, 1.5f, -1e6f}, {0, 0, 1}}) == Approx(1e6 - std::sqrt(4 - 2.25)).epsilon(1e-6));
}

TEST_CASE("disk: hits, hole, edge-on and back side", "[quadric]") {
  Quadric q = make(QuadricKind::Disk);  // radius 1, inner 0.25
  Vec2f uv;
  CHECK(hit_t(q, {{0.5f, 0, 1}, {0, 0, -1}}, &uv) == Approx(1));
  CHECK(uv.x == Approx(0).margin(1e-6));
  CHECK(uv.y == Approx((1 - 0.5) / (1 - 0.25)));
  CHECK(hit_t(q, {{0, -0.9f, -2}, {0, 0, 1}}, &uv) == Approx(2));  // the back side is hit too
  CHECK(uv.x == Approx(0.75f));
  CHECK(hit_t(q, {{0.1f, 0.1f, 1}, {0, 0, -1}}) < 0);   // in the hole
  CHECK(hit_t(q, {{1.01f, 0, 1}, {0, 0, -1}}) < 0);     // outside
  CHECK(hit_t(q, {{-3, 0.5f, 0}, {1, 0, 0}}) < 0);      // edge-on, in the plane
  CHECK(hit_t(q, {{0.5f, 0, 0}, {0, 0, 1}}) < 0);       // starts on the disk
  CHECK(hit_t(q, {{0.5f, 0, 1}, {0, 0, -1}, 1.0f}) < 0);
}

TEST_CASE("cylinder: outside, inside, open ends, grazing", "[quadric]") {
  Quadric q = make(QuadricKind::Cylinder);  // radius 1, z in [-0.5, 1.5]
  Vec2f uv;
  CHECK(hit_t(q, {{-3, 0, 0.5f}, {1, 0, 0}}, &uv) == Approx(2));
  CHECK(uv.x == Approx(0.5f));
  CHECK(uv.y == Approx(0.5f));
  CHECK(hit_t(q, {{0, 0, 0}, {1, 0, 0}}, &uv) == Approx(1));  // from inside: far wall
  CHECK(uv.x == Approx(0).margin(1e-6));
  CHECK(uv.y == Approx(0.25f));
  CHECK(hit_t(q, {{-3, 0, 2.7f}, {1, 0, -0.5f}}) == Approx(4));  // over the rim, onto the inside of the far wall
  CHECK(hit_t(q, {{0.5f, 0, -5}, {0, 0, 1}}) < 0);               // along the axis, out through the open ends
  CHECK(hit_t(q, {{0.5f, 0, -5}, {0.1f, 0, 1}}) == Approx(5));   // in through the bottom opening
  CHECK(hit_t(q, {{-3, 0, 2}, {1, 0, 0}}) < 0);                  // above the cylinder
  CHECK(hit_t(q, {{-3, 1.001f, 0}, {1, 0, 0}}) < 0);
  CHECK(hit_t(q, {{-3, 0.999f, 0}, {1, 0, 0}}) > 0);
  CHECK(hit_t(q, {{-3, 0, 0}, {1, 0, 0}, 2.0f}) < 0);
  CHECK(hit_t(q, {{1, 0, 0}, {1, 0, 0}}) < 0);                   // on the wall, leaving
  CHECK(hit_t(q, {{1, 0, 0}, {-1, 0, 0}}) == Approx(2));         // on the wall, entering
}

TEST_CASE("quadric: validate rejects bad parameters with a clear message", "[quadric]") {
  for (QuadricKind k : kKinds) CHECK_NOTHROW(validate(make(k, general_transform())));
  Quadric q = make(QuadricKind::Sphere);
  q.radius = 0;
  CHECK_THROWS_WITH(validate(q), Catch::Contains("radius"));
  q.radius = -1;
  CHECK_THROWS_AS(validate(q), Error);
  q = make(QuadricKind::Disk);
  q.inner_radius = -0.1f;
  CHECK_THROWS_WITH(validate(q), Catch::Contains("inner_radius"));
  q.inner_radius = 1;
  CHECK_THROWS_WITH(validate(q), Catch::Contains("inner_radius"));
  q = make(QuadricKind::Cylinder);
  q.z_min = q.z_max = 1;
  CHECK_THROWS_WITH(validate(q), Catch::Contains("z_min"));
  Mat4 flat;
  flat.m[2][2] = 0;  // squashes z: no inverse exists (built directly, as Transform(Mat4) would throw)
  q = make(QuadricKind::Cylinder);
  q.to_world = Transform(flat, Mat4{});
  CHECK_THROWS_WITH(validate(q), Catch::Contains("singular"));
}

// ---------------------------------------------------------------------------------------------------------------
// Quadrics under arbitrary transforms

TEST_CASE("quadric: normals are unit, outward and perpendicular to the surface", "[quadric]") {
  Pcg32 rng(11);
  for (const Transform& tf : {Transform{}, general_transform(), mirrored_transform()})
    for (QuadricKind kind : kKinds) {
      const Quadric q = make(kind, tf);
      for (int i = 0; i < 200; ++i) {
        const Vec2f uv{rng.next_float(), 0.02f + 0.96f * rng.next_float()};
        const SurfacePoint s = surface_at(q, uv);
        CHECK(length(s.n) == Approx(1).epsilon(1e-5));
        CHECK(s.uv.x == uv.x);
        // Outward: away from the axis point at the same height (sphere, cylinder); along local +z (disk).
        const Vec3f local = tf.apply_inverse_point(s.p);
        const Vec3f axis_point = tf.apply_point({0, 0, kind == QuadricKind::Sphere ? 0 : local.z});
        const Vec3f away = kind == QuadricKind::Disk ? tf.apply_vector({0, 0, 1}) : s.p - axis_point;
        CHECK(dot(s.n, normalize(away)) > 0.05f);
        // Tangents from finite differences of the parameterization are perpendicular to n.
        const float h = 1e-3f;
        const Vec3f du = surface_at(q, {uv.x + h, uv.y}).p - surface_at(q, {uv.x - h, uv.y}).p;
        const Vec3f dv = surface_at(q, {uv.x, uv.y + h}).p - surface_at(q, {uv.x, uv.y - h}).p;
        CHECK(std::fabs(dot(s.n, normalize(du))) < 2e-3f);
        CHECK(std::fabs(dot(s.n, normalize(dv))) < 2e-3f);
      }
    }
}

TEST_CASE("quadric: rays towards surface points hit them with matching t and uv", "[quadric]") {
  Pcg32 rng(5);
  for (const Transform& tf : {Transform{}, general_transform(), mirrored_transform()})
    for (QuadricKind kind : kKinds) {
      const Quadric q = make(kind, tf);
      const Bounds3f wb = world_bounds(q);
      int hits = 0;
      for (int i = 0; i < 300; ++i) {
        const Vec2f uv{rng.next_float(), 0.05f + 0.9f * rng.next_float()};
        const SurfacePoint s = surface_at(q, uv);
        CHECK(wb.contains(s.p));
        // An origin on the normal's side: for a convex solid the surface point is the first hit. The disk is
        // also hit from behind.
        Vec3f w = random_direction(rng);
        if (kind != QuadricKind::Disk && dot(w, s.n) < 0) w = -w;
        if (std::fabs(dot(w, s.n)) < 0.1f) continue;
        const Vec3f o = s.p + w * (0.5f + 3 * rng.next_float());
        Vec2f huv;
        const float t = hit_t(q, {o, s.p - o}, &huv);
        CHECK(t == Approx(1).epsilon(1e-4));
        CHECK(u_distance(huv.x, uv.x) < 1e-4f);
        CHECK(huv.y == Approx(uv.y).epsilon(1e-3));
        CHECK(huv.x >= 0);
        CHECK(huv.x <= 1);
        // A t_max just short of the hit excludes it (the nearest surface point is this one).
        CHECK(hit_t(q, {o, s.p - o, 0.999f}) < 0);
        hits += t > 0;
      }
      CHECK(hits > 150);
    }
}

TEST_CASE("quadric: rays starting on the surface and from inside, under transforms", "[quadric]") {
  Pcg32 rng(9);
  for (const Transform& tf : {general_transform(), mirrored_transform()})
    for (QuadricKind kind : kKinds) {
      const Quadric q = make(kind, tf);
      for (int i = 0; i < 200; ++i) {
        const Vec2f uv{rng.next_float(), 0.05f + 0.9f * rng.next_float()};
        const SurfacePoint s = surface_at(q, uv);
        // Leaving through the outside never re-hits the surface it starts on (convex solids; any disk ray).
        Vec3f w = random_direction(rng);
        if (dot(w, s.n) < 0) w = -w;
        CHECK(hit_t(q, {s.p, w}) < 0);
        if (kind == QuadricKind::Disk) {
          CHECK(hit_t(q, {s.p, -w}) < 0);
          continue;
        }
        // Entering: straight through the axis (cylinder: no z motion) to the opposite point.
        const Vec3f local = tf.apply_inverse_point(s.p);
        const Vec3f to_opposite = kind == QuadricKind::Sphere ? -local : Vec3f(-local.x, -local.y, 0);
        const Vec3f d = tf.apply_vector(to_opposite);
        CHECK(hit_t(q, {s.p, d}) == Approx(2).epsilon(1e-4));
        // From a random interior point in a random horizontal (cylinder) or any (sphere) local direction.
        const Vec3f inside = local * (0.9f * rng.next_float());
        Vec3f ld = random_direction(rng);
        if (kind == QuadricKind::Cylinder) ld = std::fabs(ld.z) > 0.99f ? Vec3f(1, 0, 0) : normalize({ld.x, ld.y, 0});
        Vec2f huv;
        const float t = hit_t(q, {tf.apply_point(inside), tf.apply_vector(ld)}, &huv);
        REQUIRE(t > 0);
        const Vec3f hit_local = inside + ld * t;
        CHECK(length(Vec3f(hit_local.x, hit_local.y, kind == QuadricKind::Sphere ? hit_local.z : 0)) ==
              Approx(q.radius).epsilon(1e-4));
        CHECK(distance(surface_at(q, huv).p, tf.apply_point(hit_local)) < 1e-3f);
      }
    }
}

TEST_CASE("quadric: world bounds contain the surface and are tight", "[quadric]") {
  Pcg32 rng(13);
  for (const Transform& tf : {Transform{}, general_transform(), mirrored_transform()})
    for (QuadricKind kind : kKinds) {
      const Quadric q = make(kind, tf);
      const Bounds3f wb = world_bounds(q);
      Bounds3f seen;
      for (int i = 0; i < 20000; ++i) {
        const Vec3f p = surface_at(q, {rng.next_float(), i % 100 == 0 ? 1.0f : rng.next_float()}).p;
        INFO("kind " << int(kind) << " point " << p.x << " " << p.y << " " << p.z);
        CHECK(wb.contains(p));
        seen.extend(p);
      }
      // The samples come within 1% of the box's extent on every side (the transformed object box would not).
      const float tol = 0.01f * max_component(wb.diagonal());
      for (int a = 0; a < 3; ++a) {
        CHECK(seen.lo[a] - wb.lo[a] < tol);
        CHECK(wb.hi[a] - seen.hi[a] < tol);
      }
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Area and area sampling

TEST_CASE("quadric: area is exact under similarity transforms", "[quadric][area]") {
  const Transform sim = translate({3, -1, 2}) * rotate(50, {1, -2, 1}) * scale({2.5f, 2.5f, 2.5f});
  const Transform mirror = rotate(20, {0, 1, 1}) * scale({-0.5f, 0.5f, 0.5f});
  for (const Transform& tf : {Transform{}, sim, mirror}) {
    const double s2 = std::pow(std::fabs(double(tf.determinant3())), 2.0 / 3.0);
    CHECK(area(make(QuadricKind::Sphere, tf)) == Approx(4 * kPi * s2).epsilon(1e-5));
    CHECK(area(make(QuadricKind::Disk, tf)) == Approx(kPi * (1 - 0.0625) * s2).epsilon(1e-5));
    CHECK(area(make(QuadricKind::Cylinder, tf)) == Approx(2 * kPi * 2 * s2).epsilon(1e-5));
  }
  // A disk under any affine map and a cylinder stretched along its axis stay exact too.
  CHECK(area(make(QuadricKind::Disk, scale({2, 3, 5}))) == Approx(kPi * (1 - 0.0625) * 6).epsilon(1e-5));
  CHECK(area(make(QuadricKind::Cylinder, scale({2, 2, 3}))) == Approx(2 * kPi * 2 * 2 * 3).epsilon(1e-5));
}

namespace {

// Surface area of the ellipsoid with semi-axes (a, b, c) by the midpoint rule on (theta, phi).
double ellipsoid_area(double a, double b, double c) {
  constexpr int n = 1500;
  const double pi = 3.14159265358979323846, dt = pi / n, dp = 2 * pi / (2 * n);
  std::vector<double> cos2(2 * n);
  for (int j = 0; j < 2 * n; ++j) cos2[j] = std::pow(std::cos((j + 0.5) * dp), 2);
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double th = (i + 0.5) * dt, st = std::sin(th), ct = std::cos(th);
    for (int j = 0; j < 2 * n; ++j) {
      const double cp2 = cos2[j], sp2 = 1 - cp2;
      sum += st * std::sqrt(st * st * (b * b * c * c * cp2 + a * a * c * c * sp2) + a * a * b * b * ct * ct);
    }
  }
  return sum * dt * dp;
}

}  // namespace

TEST_CASE("quadric: under non-uniform scale, the mean of 1/pdf is the world area and pdf_area matches", "[quadric][area]") {
  const double reference = ellipsoid_area(1, 2, 3);
  CHECK(reference == Approx(48.88).epsilon(1e-3));  // Knud Thomsen's approximation, as a sanity check
  const Quadric q = make(QuadricKind::Sphere, translate({1, 2, 3}) * rotate(30, {1, 1, 1}) * scale({1, 2, 3}));
  CHECK(area(q) == Approx(reference).epsilon(1e-3));
  Pcg32 rng(21);
  constexpr int n = 200000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    float pdf = 0;
    const SurfacePoint s = sample_area(q, {rng.next_float(), rng.next_float()}, &pdf);
    REQUIRE(pdf > 0);
    sum += 1.0 / pdf;
    if (i % 64 == 0) {
      CHECK(pdf_area(q, s.uv) == Approx(pdf).epsilon(1e-6));
      CHECK(distance(surface_at(q, s.uv).p, s.p) < 1e-5f);
    }
  }
  CHECK(sum / n == Approx(reference).epsilon(0.01));
  // The elliptic cylinder: the reference perimeter of the ellipse (1, 2) times the height.
  double perimeter = 0;
  for (int j = 0; j < 100000; ++j) {
    const double ph = (j + 0.5) * 2 * 3.14159265358979323846 / 100000;
    perimeter += std::hypot(std::sin(ph), 2 * std::cos(ph)) * 2 * 3.14159265358979323846 / 100000;
  }
  const Quadric cyl = make(QuadricKind::Cylinder, rotate(40, {0, 1, 1}) * scale({1, 2, 0.5f}));
  CHECK(area(cyl) == Approx(perimeter * 2 * 0.5).epsilon(1e-5));
}

TEST_CASE("quadric: sphere samples are uniform in object-space (cos theta, phi)", "[quadric][sampling]") {
  const Transform sim = translate({-2, 0, 1}) * rotate(70, {1, 0, 1}) * scale({1.7f, 1.7f, 1.7f});
  int test_index = 0;
  for (const Transform& tf : {sim, general_transform()}) {
    const Quadric q = make(QuadricKind::Sphere, tf);
    constexpr int nz = 16, np = 16, n = 100000;
    std::vector<double> observed(nz * np, 0), expected(nz * np, double(n) / (nz * np));
    Pcg32 rng(100 + test_index++);
    for (int i = 0; i < n; ++i) {
      const Vec3f p = tf.apply_inverse_point(sample_area(q, {rng.next_float(), rng.next_float()}, nullptr).p);
      const double z = std::clamp(double(p.z) / length(p), -1.0, 1.0);
      double phi = std::atan2(double(p.y), double(p.x));
      if (phi < 0) phi += 2 * 3.14159265358979323846;
      const int iz = std::min(nz - 1, int((z + 1) / 2 * nz));
      const int ip = std::min(np - 1, int(phi / (2 * 3.14159265358979323846) * np));
      observed[iz * np + ip] += 1;
    }
    const auto r = test::chi2_test(observed, expected, 0.01, 2);
    INFO(r.message);
    CHECK(r.passed);
  }
}

TEST_CASE("quadric: sample_area matches pdf_area integrated over world area (chi-square)", "[quadric][sampling]") {
  // Expected counts come from integrating pdf_area against the world-space area element |dp/du x dp/dv|,
  // measured by finite differences of surface_at: this checks the pdf in world measure, so a wrong area
  // scale factor fails even though the samples themselves are uniform in object space.
  constexpr int nu = 12, nv = 12, sub = 6, n = 60000;
  int seed = 0;
  for (const Transform& tf : {general_transform(), mirrored_transform()})
    for (QuadricKind kind : kKinds) {
      const Quadric q = make(kind, tf);
      std::vector<double> observed(nu * nv, 0), expected(nu * nv, 0);
      const double du = 1.0 / (nu * sub), dv = 1.0 / (nv * sub);
      const float h = 2e-3f;
      for (int i = 0; i < nu * sub; ++i)
        for (int j = 0; j < nv * sub; ++j) {
          const Vec2f uv{float((i + 0.5) * du), float((j + 0.5) * dv)};
          const Vec3f pu = (surface_at(q, {uv.x + h, uv.y}).p - surface_at(q, {uv.x - h, uv.y}).p) / (2 * h);
          const Vec3f pv = (surface_at(q, {uv.x, uv.y + h}).p - surface_at(q, {uv.x, uv.y - h}).p) / (2 * h);
          expected[(i / sub) * nv + j / sub] += double(pdf_area(q, uv)) * length(cross(pu, pv)) * du * dv * n;
        }
      Pcg32 rng(42 + seed++);
      for (int k = 0; k < n; ++k) {
        const Vec2f uv = sample_area(q, {rng.next_float(), rng.next_float()}, nullptr).uv;
        observed[std::min(nu - 1, int(uv.x * nu)) * nv + std::min(nv - 1, int(uv.y * nv))] += 1;
      }
      double total = 0;
      for (double e : expected) total += e;
      CHECK(total == Approx(n).epsilon(2e-3));  // pdf_area integrates to one over the world surface
      const auto r = test::chi2_test(observed, expected, 0.01, 6);
      INFO("kind " << int(kind) << ": " << r.message);
      CHECK(r.passed);
    }
}
