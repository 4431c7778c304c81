// Unit tests for the math core: vectors, frames, bounds and their slab test, matrices and transforms, PCG32.
#include <catch2/catch.hpp>

#include <cmath>
#include <set>
#include <vector>

#include "core/bounds.h"
#include "core/error.h"
#include "core/rng.h"
#include "core/transform.h"
#include "core/vec.h"

using namespace torte;

namespace {

// Componentwise comparison with an absolute tolerance (values in these tests are O(1)..O(1000)).
bool near(Vec3f a, Vec3f b, float eps = 1e-5f) {
  return std::fabs(a.x - b.x) <= eps && std::fabs(a.y - b.y) <= eps && std::fabs(a.z - b.z) <= eps;
}

Vec3f random_vec(Pcg32& rng, float lo = -1, float hi = 1) {
  auto f = [&] { return lo + (hi - lo) * rng.next_float(); };
  const float x = f(), y = f(), z = f();  // sequenced: argument evaluation order is unspecified
  return {x, y, z};
}

Vec3f random_unit(Pcg32& rng) {
  for (;;) {
    const Vec3f v = random_vec(rng);
    const float l2 = length_squared(v);
    if (l2 > 1e-4f && l2 <= 1) return v / std::sqrt(l2);
  }
}

// A random affine matrix whose 3x3 part is diagonally dominant, hence well conditioned.
Mat4 random_affine(Pcg32& rng) {
  Mat4 m;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m.m[i][j] = 2 * rng.next_float() - 1 + (i == j ? 4.0f : 0.0f);
    m.m[i][3] = 20 * rng.next_float() - 10;
  }
  return m;
}

bool near_identity(const Mat4& m, float eps) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (std::fabs(m.m[i][j] - (i == j ? 1.0f : 0.0f)) > eps) return false;
  return true;
}

}  // namespace

TEST_CASE("Vec3f arithmetic, dot and cross", "[math][vec]") {
  const Vec3f a(1, 2, 3), b(-4, 5, 0.5f);
  CHECK(a + b == Vec3f(-3, 7, 3.5f));
  CHECK(a - b == Vec3f(5, -3, 2.5f));
  CHECK(-a == Vec3f(-1, -2, -3));
  CHECK(2.0f * a == Vec3f(2, 4, 6));
  CHECK(a / 2 == Vec3f(0.5f, 1, 1.5f));
  CHECK(mul(a, b) == Vec3f(-4, 10, 1.5f));
  CHECK(dot(a, b) == Approx(-4 + 10 + 1.5));
  // Right-handed: x cross y = z (and cyclic).
  CHECK(cross({1, 0, 0}, {0, 1, 0}) == Vec3f(0, 0, 1));
  CHECK(cross({0, 1, 0}, {0, 0, 1}) == Vec3f(1, 0, 0));
  CHECK(cross({0, 0, 1}, {1, 0, 0}) == Vec3f(0, 1, 0));
  const Vec3f c = cross(a, b);
  CHECK(dot(c, a) == Approx(0).margin(1e-5));
  CHECK(dot(c, b) == Approx(0).margin(1e-5));
  CHECK(length(Vec3f(3, 4, 12)) == Approx(13));
  CHECK(length(normalize(b)) == Approx(1));
  CHECK(distance(a, b) == Approx(length(a - b)));
  Vec3f d = a;
  d += b;
  d -= a;
  d *= 2;
  CHECK(d == b * 2);
  CHECK(d[0] == d.x);
  CHECK(d[2] == d.z);
}

TEST_CASE("Vec3f component helpers", "[math][vec]") {
  CHECK(min(Vec3f(1, 5, -2), Vec3f(3, 0, -1)) == Vec3f(1, 0, -2));
  CHECK(max(Vec3f(1, 5, -2), Vec3f(3, 0, -1)) == Vec3f(3, 5, -1));
  CHECK(abs(Vec3f(-1, 2, -3)) == Vec3f(1, 2, 3));
  CHECK(max_component(Vec3f(1, 7, 3)) == 7);
  CHECK(max_dimension(Vec3f(9, 7, 3)) == 0);
  CHECK(max_dimension(Vec3f(1, 7, 3)) == 1);
  CHECK(max_dimension(Vec3f(1, 7, 30)) == 2);
  CHECK(is_finite(Vec3f(1, 2, 3)));
  CHECK_FALSE(is_finite(Vec3f(1, kInfinity, 3)));
  CHECK_FALSE(is_finite(Vec3f(std::nanf(""), 0, 0)));
  CHECK(face_forward({0, 0, 1}, {0.3f, 0, -1}) == Vec3f(0, 0, -1));
  CHECK(face_forward({0, 0, 1}, {0.3f, 0, 1}) == Vec3f(0, 0, 1));
}

TEST_CASE("Frame::from_z is a right-handed orthonormal basis", "[math][vec]") {
  Pcg32 rng(7);
  std::vector<Vec3f> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}, normalize(Vec3f(1e-4f, 0, -1)),
                                normalize(Vec3f(0, 1e-4f, 1))};
  for (int i = 0; i < 1000; ++i) normals.push_back(random_unit(rng));
  for (const Vec3f& n : normals) {
    INFO("n = (" << n.x << ", " << n.y << ", " << n.z << ")");
    const Frame f = Frame::from_z(n);
    CHECK(f.n == n);
    CHECK(length(f.s) == Approx(1).margin(1e-5));
    CHECK(length(f.t) == Approx(1).margin(1e-5));
    CHECK(dot(f.s, f.t) == Approx(0).margin(1e-5));
    CHECK(dot(f.s, f.n) == Approx(0).margin(1e-5));
    CHECK(dot(f.t, f.n) == Approx(0).margin(1e-5));
    CHECK(near(cross(f.s, f.t), f.n, 1e-5f));
    const Vec3f v = random_vec(rng);
    CHECK(near(f.to_world(f.to_local(v)), v, 1e-5f));
    CHECK(near(f.to_local(n), Vec3f(0, 0, 1), 1e-5f));
  }
}

TEST_CASE("Bounds3f extend, merge, area and containment", "[math][bounds]") {
  Bounds3f b;
  CHECK(b.empty());
  CHECK(b.surface_area() == 0);
  b.extend({1, 2, 3});
  CHECK_FALSE(b.empty());
  CHECK(b.surface_area() == 0);  // a single point
  b.extend({-1, 4, 4});
  CHECK(b.lo == Vec3f(-1, 2, 3));
  CHECK(b.hi == Vec3f(1, 4, 4));
  CHECK(b.diagonal() == Vec3f(2, 2, 1));
  CHECK(b.center() == Vec3f(0, 3, 3.5f));
  CHECK(b.surface_area() == Approx(2 * (4 + 2 + 2)));
  CHECK(b.contains({0, 3, 3.5f}));
  CHECK(b.contains(b.lo));
  CHECK(b.contains(b.hi));
  CHECK_FALSE(b.contains({0, 3, 4.01f}));
  Bounds3f c;
  c.extend({5, 5, 5});
  const Bounds3f m = merge(b, c);
  CHECK(m.lo == Vec3f(-1, 2, 3));
  CHECK(m.hi == Vec3f(5, 5, 5));
  CHECK(merge(b, Bounds3f{}).lo == b.lo);  // merging an empty box changes nothing
  CHECK(merge(b, Bounds3f{}).hi == b.hi);
}

namespace {
bool hits(const Bounds3f& b, Vec3f o, Vec3f d, float t_max = kInfinity, float* t_near = nullptr) {
  return b.intersect(o, Vec3f(1 / d.x, 1 / d.y, 1 / d.z), t_max, t_near);
}
}  // namespace

TEST_CASE("Bounds3f slab test: hits and misses", "[math][bounds]") {
  Bounds3f b;
  b.extend({0, 0, 0});
  b.extend({1, 1, 1});
  float t = -1;
  REQUIRE(hits(b, {-1, 0.5f, 0.5f}, {1, 0, 0}, kInfinity, &t));
  CHECK(t == Approx(1));
  REQUIRE(hits(b, {2, 0.5f, 0.5f}, {-1, 0, 0}, kInfinity, &t));  // negative direction
  CHECK(t == Approx(1));
  REQUIRE(hits(b, {0.5f, 0.5f, 0.5f}, normalize(Vec3f(1, -2, 3)), kInfinity, &t));  // origin inside
  CHECK(t == 0);
  CHECK(hits(b, {-1, -1, -1}, normalize(Vec3f(1, 1, 1))));
  CHECK_FALSE(hits(b, {-1, 1.5f, 0.5f}, {1, 0, 0}));     // passes above
  CHECK_FALSE(hits(b, {-1, 0.5f, 0.5f}, {-1, 0, 0}));    // box is behind the origin
  CHECK_FALSE(hits(b, {-1, 0.5f, 0.5f}, {1, 0, 0}, 0.5f));  // t_max ends before the box
  CHECK(hits(b, {-1, 0.5f, 0.5f}, {1, 0, 0}, 1.5f));
  CHECK_FALSE(hits(b, {-1, -1, 0.5f}, normalize(Vec3f(1, -1, 0))));  // diagonal away from the box
}

TEST_CASE("Bounds3f slab test: grazing rays count as hits", "[math][bounds]") {
  Bounds3f b;
  b.extend({0, 0, 0});
  b.extend({1, 1, 1});
  // Axis-parallel rays in a face plane and along an edge: 1/d is infinite, and 0 * inf = NaN must not reject.
  CHECK(hits(b, {-1, 0.5f, 1}, {1, 0, 0}));
  CHECK(hits(b, {-1, 0.5f, 0}, {1, 0, 0}));
  CHECK(hits(b, {-1, 1, 1}, {1, 0, 0}));
  CHECK(hits(b, {0, 0, -3}, {0, 0, 1}));
  // Diagonal ray touching only the edge x = y = 1: the slabs overlap in the single instant t = 1.
  float t = -1;
  REQUIRE(hits(b, {0, 2, 0.5f}, {1, -1, 0}, kInfinity, &t));
  CHECK(t == Approx(1));
  // ... and a near-miss just outside it.
  CHECK_FALSE(hits(b, {0, 2.001f, 0.5f}, {1, -1, 0}));
  CHECK_FALSE(hits(b, {-1, 1.0001f, 0.5f}, {1, 0, 0}));
}

TEST_CASE("Mat4 inverse of random well-conditioned matrices", "[math][transform]") {
  Pcg32 rng(12345);
  for (int k = 0; k < 200; ++k) {
    const Mat4 m = random_affine(rng);
    const Mat4 inv = inverse(m);
    CHECK(near_identity(m * inv, 1e-5f));
    CHECK(near_identity(inv * m, 1e-5f));
  }
  // A general (projective) 4x4 matrix needing row pivoting: zero on the diagonal.
  Mat4 p;
  const float rows[4][4] = {{0, 2, 0, 1}, {1, 0, 0, 0}, {0, 0, 0, 3}, {0, 1, 4, 0}};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) p.m[i][j] = rows[i][j];
  CHECK(near_identity(p * inverse(p), 1e-6f));
  CHECK(inverse(Mat4::identity()).is_identity());
  CHECK(transpose(transpose(p)) == p);
  CHECK(transpose(p).m[0][1] == p.m[1][0]);
}

TEST_CASE("Singular matrices throw", "[math][transform]") {
  // Row 2 of the 3x3 part is row 0 + 2 row 1, and the z column is all zero: rank 3 of 4.
  Mat4 dependent;
  dependent.m[2][0] = 1;
  dependent.m[2][1] = 2;
  dependent.m[2][2] = 0;
  CHECK_THROWS_AS(inverse(dependent), Error);
  CHECK_THROWS_AS(Transform(dependent), Error);
  Mat4 zero_row;
  zero_row.m[1][1] = 0;
  CHECK_THROWS_AS(inverse(zero_row), Error);
  CHECK_THROWS_AS(scale({1, 0, 1}), Error);
  CHECK_THROWS_AS(rotate(30, {0, 0, 0}), Error);
}

TEST_CASE("translate, scale and rotate on points, vectors and normals", "[math][transform]") {
  const Transform t = translate({1, 2, 3});
  CHECK(t.apply_point({1, 1, 1}) == Vec3f(2, 3, 4));
  CHECK(t.apply_vector({1, 1, 1}) == Vec3f(1, 1, 1));  // vectors ignore translation
  CHECK(t.apply_normal({0, 0, 1}) == Vec3f(0, 0, 1));
  CHECK(t.apply_inverse_point({2, 3, 4}) == Vec3f(1, 1, 1));
  CHECK(t.inverse().apply_point({2, 3, 4}) == Vec3f(1, 1, 1));

  const Transform s = scale({2, 3, 4});
  CHECK(s.apply_point({1, 1, 1}) == Vec3f(2, 3, 4));
  CHECK(s.apply_vector({1, -1, 2}) == Vec3f(2, -3, 8));
  CHECK(s.apply_inverse_vector({2, 3, 4}) == Vec3f(1, 1, 1));
  CHECK(s.determinant3() == Approx(24));
  CHECK(scale({-1, 1, 1}).determinant3() == Approx(-1));  // handedness flip

  // Rotations are right-handed: +90 degrees about z takes x to y, about x takes y to z, about y takes z to x.
  CHECK(near(rotate(90, {0, 0, 1}).apply_vector({1, 0, 0}), {0, 1, 0}));
  CHECK(near(rotate(90, {1, 0, 0}).apply_vector({0, 1, 0}), {0, 0, 1}));
  CHECK(near(rotate(90, {0, 1, 0}).apply_vector({0, 0, 1}), {1, 0, 0}));
  CHECK(near(rotate(90, {0, 0, 5}).apply_point({1, 0, 7}), {0, 1, 7}));  // axis need not be unit length

  Pcg32 rng(99);
  for (int k = 0; k < 100; ++k) {
    const Vec3f axis = random_unit(rng);
    const float deg = 340 * rng.next_float() - 170;  // away from the atan2 wrap at 180
    const Transform r = rotate(deg, axis);
    const Vec3f v = random_vec(rng);
    CHECK(near(r.apply_vector(axis), axis));                     // the axis is fixed
    CHECK(length(r.apply_vector(v)) == Approx(length(v)).epsilon(1e-5));  // lengths are preserved
    CHECK(near(r.apply_inverse_vector(r.apply_vector(v)), v));   // the stored inverse is the transpose
    CHECK(r.determinant3() == Approx(1).epsilon(1e-5));
    // The angle between v and its image, measured in the plane perpendicular to the axis, is deg.
    const Vec3f vp = v - axis * dot(v, axis), rp = r.apply_vector(vp);
    if (length(vp) > 0.1f) {
      const float angle = std::atan2(dot(cross(vp, rp), axis), dot(vp, rp)) * 180 / kPi;
      CHECK(angle == Approx(deg).margin(1e-3));
    }
  }
}

TEST_CASE("Normals stay perpendicular to surfaces under non-uniform transforms", "[math][transform]") {
  Pcg32 rng(2024);
  const Transform xf = rotate(33, {1, 2, 3}) * scale({0.5f, 3, 7}) * rotate(-71, {0, 1, 1}) * translate({4, 5, 6});
  for (int k = 0; k < 200; ++k) {
    const Vec3f t1 = random_unit(rng);
    const Vec3f t2 = normalize(cross(t1, random_unit(rng)));
    const Vec3f n = cross(t1, t2);
    const Vec3f n2 = normalize(xf.apply_normal(n));
    CHECK(dot(n2, normalize(xf.apply_vector(t1))) == Approx(0).margin(1e-5));
    CHECK(dot(n2, normalize(xf.apply_vector(t2))) == Approx(0).margin(1e-5));
  }
  // Mapping a normal like a vector would tilt it off the surface; the inverse transpose does not.
  const Transform s = scale({1, 4, 1});
  const Vec3f n = normalize(Vec3f(1, 1, 0));  // normal of the plane x + y = c, tangent (1, -1, 0)
  CHECK(dot(normalize(s.apply_normal(n)), normalize(s.apply_vector({1, -1, 0}))) == Approx(0).margin(1e-6));
  CHECK(std::fabs(dot(normalize(s.apply_vector(n)), normalize(s.apply_vector({1, -1, 0})))) > 0.5f);
}

TEST_CASE("Transform composition order: the right operand applies first", "[math][transform]") {
  const Transform t = translate({10, 0, 0}), s = scale({2, 2, 2});
  CHECK((t * s).apply_point({1, 1, 1}) == Vec3f(12, 2, 2));  // scale, then translate
  CHECK((s * t).apply_point({1, 1, 1}) == Vec3f(22, 2, 2));  // translate, then scale
  Pcg32 rng(5);
  const Transform a(random_affine(rng)), b(random_affine(rng)), c = rotate(40, {1, 1, 0});
  for (int k = 0; k < 50; ++k) {
    const Vec3f p = random_vec(rng, -10, 10);
    CHECK(near((a * b * c).apply_point(p), a.apply_point(b.apply_point(c.apply_point(p))), 1e-3f));
    // (a b)^-1 = b^-1 a^-1, kept alongside by operator*.
    CHECK(near((a * b).apply_inverse_point((a * b).apply_point(p)), p, 1e-4f));
    CHECK(near_identity((a * b).matrix() * (a * b).inverse_matrix(), 1e-5f));
  }
  CHECK((t * t.inverse()).is_identity());
  CHECK(Transform().is_identity());
}

TEST_CASE("Transform applied to rays and bounds", "[math][transform]") {
  const Transform xf = translate({1, 0, 0}) * scale({2, 2, 2});
  const Ray r = xf.apply_inverse(Ray{{3, 2, 0}, {0, 4, 0}, 5});
  CHECK(r.o == Vec3f(1, 1, 0));
  CHECK(r.d == Vec3f(0, 2, 0));
  CHECK(r.t_max == 5);  // t is unchanged because d is not renormalized

  Bounds3f unit;
  unit.extend({0, 0, 0});
  unit.extend({1, 1, 1});
  const Bounds3f rb = rotate(45, {0, 0, 1}).apply(unit);
  const float h = std::sqrt(0.5f);
  CHECK(near(rb.lo, {-h, 0, 0}));
  CHECK(near(rb.hi, {h, 2 * h, 1}));
  CHECK(xf.apply(Bounds3f{}).empty());
}

TEST_CASE("look_at builds the world-from-camera transform", "[math][transform]") {
  // The Cornell box camera.
  const Vec3f eye(278, 273, -800), target(278, 273, 0);
  const Transform cam = look_at(eye, target, {0, 1, 0});
  CHECK(near(cam.apply_point({0, 0, 0}), eye, 1e-3f));
  CHECK(near(cam.apply_vector({0, 0, 1}), {0, 0, 1}));
  CHECK(near(cam.apply_vector({1, 0, 0}), {1, 0, 0}));
  CHECK(near(cam.apply_vector({0, 1, 0}), {0, 1, 0}));
  CHECK(near(cam.apply_point({0, 0, 800}), target, 1e-3f));
  CHECK(near(cam.apply_inverse_point(target), {0, 0, 800}, 1e-3f));

  // A general view: orthonormal, right-handed, forward towards the target, up in the (up, forward) plane.
  const Vec3f e2(1, 2, 3), t2(-4, 0.5f, 7), up(0.2f, 1, 0.1f);
  const Transform c2 = look_at(e2, t2, up);
  const Vec3f x = c2.apply_vector({1, 0, 0}), y = c2.apply_vector({0, 1, 0}), z = c2.apply_vector({0, 0, 1});
  CHECK(near(z, normalize(t2 - e2)));
  CHECK(length(x) == Approx(1));
  CHECK(length(y) == Approx(1));
  CHECK(dot(x, y) == Approx(0).margin(1e-6));
  CHECK(near(cross(x, y), z));
  CHECK(dot(y, up) > 0);
  CHECK(dot(x, up) == Approx(0).margin(1e-6));
  CHECK(c2.determinant3() == Approx(1));

  CHECK_THROWS_AS(look_at({0, 0, 0}, {0, 5, 0}, {0, 1, 0}), Error);
  CHECK_THROWS_AS(look_at({1, 1, 1}, {1, 1, 1}, {0, 1, 0}), Error);
}

TEST_CASE("area_scale gives the growth of surface elements", "[math][transform]") {
  const Transform s = scale({2, 3, 4});
  CHECK(s.area_scale({0, 0, 1}) == Approx(6));   // an xy element scales by 2 * 3
  CHECK(s.area_scale({1, 0, 0}) == Approx(12));  // a yz element by 3 * 4
  CHECK(s.area_scale({0, -1, 0}) == Approx(8));
  CHECK(rotate(37, {1, 2, 3}).area_scale(normalize(Vec3f(1, 1, 1))) == Approx(1));
  CHECK(translate({5, 6, 7}).area_scale({0, 1, 0}) == Approx(1));
  CHECK(scale({-2, 1, 1}).area_scale({0, 0, 1}) == Approx(2));  // mirroring does not make areas negative

  // In general: the area of the image of the unit parallelogram spanned by two tangents.
  Pcg32 rng(77);
  const Transform xf = rotate(20, {0, 1, 0}) * scale({0.3f, 2, 5}) * rotate(65, {1, 1, 1});
  for (int k = 0; k < 100; ++k) {
    const Vec3f t1 = random_unit(rng);
    const Vec3f t2 = normalize(cross(t1, random_unit(rng)));
    const float expected = length(cross(xf.apply_vector(t1), xf.apply_vector(t2)));
    CHECK(xf.area_scale(cross(t1, t2)) == Approx(expected).epsilon(1e-4));
  }
}

TEST_CASE("Pcg32 matches the reference generator and is deterministic", "[math][rng]") {
  // First outputs of O'Neill's pcg32-demo, pcg32_srandom_r(&rng, 42, 54).
  Pcg32 ref(42, 54);
  for (uint32_t expected : {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u, 0x83d2f293u, 0xbfa4784bu, 0xcbed606eu})
    CHECK(ref.next_u32() == expected);

  Pcg32 a(1234, 5), b(1234, 5), other_stream(1234, 6), other_seed(1235, 5);
  int same_stream = 0, same_seed = 0;
  for (int i = 0; i < 1000; ++i) {
    const uint32_t x = a.next_u32();
    REQUIRE(x == b.next_u32());
    same_stream += x == other_stream.next_u32();
    same_seed += x == other_seed.next_u32();
  }
  CHECK(same_stream < 3);
  CHECK(same_seed < 3);
  Pcg32 d1, d2;
  CHECK(d1.next_u32() == d2.next_u32());
}

TEST_CASE("Pcg32 floats lie in the unit interval, 1 excluded, and look uniform", "[math][rng]") {
  Pcg32 rng(3, 17);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  float lo = 1, hi = 0;
  std::set<uint32_t> distinct;
  for (int i = 0; i < n; ++i) {
    const float u = rng.next_float();
    REQUIRE(u >= 0.0f);
    REQUIRE(u < 1.0f);
    lo = std::min(lo, u);
    hi = std::max(hi, u);
    sum += u;
    sum2 += double(u) * u;
    if (i < 1000) distinct.insert(rng.next_u32());
  }
  CHECK(sum / n == Approx(0.5).margin(0.005));
  CHECK(sum2 / n - (sum / n) * (sum / n) == Approx(1.0 / 12).margin(0.002));
  CHECK(lo < 1e-4f);
  CHECK(hi > 1 - 1e-4f);
  CHECK(distinct.size() == 1000);
  CHECK(mix_bits(1) != mix_bits(2));
  CHECK(mix_bits(0) == 0);  // documented property of the Murmur finalizer: zero is its fixed point
}
