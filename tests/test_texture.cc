// Textures (core only): patterns, noise, mappings, colour maps, arithmetic, composition and its type checks,
// flattening with deduplication, and the constant fast path.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>

#include "core/error.h"
#include "core/rng.h"
#include "texture/color_map.h"
#include "texture/mapping.h"
#include "texture/noise.h"
#include "texture/texture.h"

using namespace torte;
namespace tx = torte::texture;

namespace {

// Evaluates a closed texture at a context, through a table of its own.
Rgb eval_color(const TexturePtr& t, const TextureContext& ctx) {
  TextureTableBuilder b;
  const ColorParam p = b.add(ColorInput{Rgb(), t});
  const TextureTable table = b.finish();
  return table.eval(p, ctx);
}
float eval_float(const TexturePtr& t, const TextureContext& ctx) {
  TextureTableBuilder b;
  const FloatParam p = b.add(FloatInput{0, t});
  const TextureTable table = b.finish();
  return table.eval(p, ctx);
}
TextureContext at_uv(float u, float v) {
  TextureContext c;
  c.uv = {u, v};
  return c;
}
TextureContext at_p(Vec3f p) {
  TextureContext c;
  c.p = p;
  return c;
}

// An image whose colour is its lookup coordinates and filter width: (s, t, width).
struct CoordImage : ImageSource {
  Rgb lookup(Vec2f st, float w) const override { return {st.x, st.y, w}; }
};

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("texture: 2D checker over uv, default input and scale", "[texture]") {
  const Rgb red(1, 0, 0), blue(0, 0, 1);
  const TexturePtr c = tx::checker(tx::constant(red), tx::constant(blue), 2);
  CHECK(c->input == ValueType::Vec2);
  CHECK(c->output == ValueType::Rgb);
  CHECK(eval_color(c, at_uv(0.5f, 0.5f)) == red);    // cell (0, 0): even
  CHECK(eval_color(c, at_uv(1.5f, 0.5f)) == blue);   // (1, 0)
  CHECK(eval_color(c, at_uv(1.5f, 1.5f)) == red);    // (1, 1)
  CHECK(eval_color(c, at_uv(-0.5f, 0.5f)) == blue);  // (-1, 0): floor, not truncation
  const TexturePtr fine = tx::compose(tx::checker(tx::constant(red), tx::constant(blue), 2, 2), tx::uv({2, 1}));
  // u' = 4 u, v' = 2 v cells: (0.3, 0.1) -> (1.2, 0.2) -> cell (1, 0) odd.
  CHECK(eval_color(fine, at_uv(0.3f, 0.1f)) == blue);
  CHECK(eval_color(fine, at_uv(0.2f, 0.1f)) == red);
  // Scalar colours give a scalar checker, usable as a FloatInput.
  const TexturePtr s = tx::checker(tx::constant(0.75f), tx::constant(0.25f), 2);
  CHECK(s->output == ValueType::Float);
  CHECK(eval_float(s, at_uv(0.5f, 0.5f)) == 0.75f);
  CHECK(eval_float(s, at_uv(0.5f, 1.5f)) == 0.25f);
}

TEST_CASE("texture: 3D checker over the world point, with sub-textures", "[texture]") {
  // a is itself a 2D checker (closed with uv), b a constant: a 3D cell picks which one is evaluated.
  const TexturePtr inner = tx::checker(tx::constant(0.9f), tx::constant(0.6f), 2);
  const TexturePtr c = tx::checker(inner, tx::constant(0.1f), 3);
  CHECK(c->input == ValueType::Vec3);
  TextureContext ctx = at_p({0.5f, 0.5f, 0.5f});
  ctx.uv = {1.5f, 0.5f};
  CHECK(eval_float(c, ctx) == 0.6f);  // even 3D cell -> inner checker at uv cell (1, 0) -> 0.6
  ctx.p = {1.5f, 0.5f, 0.5f};
  CHECK(eval_float(c, ctx) == 0.1f);
  ctx.p = {1.5f, -0.5f, 0.5f};
  CHECK(eval_float(c, ctx) == 0.6f);
  // Through a transform: xyz{scale 2} halves the point, so p.x = 1.5 lands in cell 0.
  const TexturePtr big = tx::compose(c, tx::xyz(torte::scale({2, 2, 2})));
  ctx.p = {1.5f, 0.5f, 0.5f};
  CHECK(eval_float(big, ctx) == 0.6f);
}

TEST_CASE("texture: noise is deterministic, bounded and continuous", "[texture][noise]") {
  Pcg32 rng(7);
  float lo = 1, hi = -1;
  for (int i = 0; i < 20000; ++i) {
    const Vec3f p(rng.next_float() * 40 - 20, rng.next_float() * 40 - 20, rng.next_float() * 40 - 20);
    for (float n : {value_noise(p), perlin_noise(p), value_noise(Vec2f(p.x, p.y)), perlin_noise(Vec2f(p.x, p.y))}) {
      REQUIRE(n >= -1.0f);
      REQUIRE(n <= 1.0f);
      lo = std::min(lo, n);
      hi = std::max(hi, n);
    }
    // Same input, same output; another seed, another field.
    REQUIRE(perlin_noise(p, 3) == perlin_noise(p, 3));
    // Continuity: a small step changes the value by a bounded amount (gradient bound of the quintic blend).
    const Vec3f q = p + Vec3f(1e-3f, -1e-3f, 1e-3f);
    REQUIRE(std::fabs(perlin_noise(q) - perlin_noise(p)) < 0.02f);
    REQUIRE(std::fabs(value_noise(q) - value_noise(p)) < 0.02f);
  }
  CHECK(lo < -0.6f);  // the range is actually used
  CHECK(hi > 0.6f);
  int differ = 0;
  for (int i = 0; i < 100; ++i) differ += perlin_noise(Vec3f(i * 0.37f + 0.1f, 0.2f, 0.3f), 1) != perlin_noise(Vec3f(i * 0.37f + 0.1f, 0.2f, 0.3f), 2);
  CHECK(differ > 90);
  // Perlin noise vanishes on the lattice; value noise there is the lattice value, the same from both sides.
  CHECK(perlin_noise(Vec3f(3, -2, 5)) == 0.0f);
  CHECK(perlin_noise(Vec2f(-4, 7)) == 0.0f);
  CHECK(value_noise(Vec3f(2 - 1e-5f, 1, 1)) == Approx(value_noise(Vec3f(2, 1, 1))).margin(1e-3));
  // Pinned values: platform-independent integer hashing, so these never change.
  CHECK(perlin_noise(Vec3f(0.5f, 0.25f, 0.125f)) == Approx(-0.243047133).margin(1e-6));
  CHECK(value_noise(Vec3f(0.5f, 0.25f, 0.125f)) == Approx(-0.449069262).margin(1e-6));
  CHECK(perlin_noise(Vec2f(0.3f, 0.7f), 5) == Approx(0.0797628239).margin(1e-6));
  CHECK(value_noise(Vec2f(0.3f, 0.7f), 5) == Approx(-0.556204855).margin(1e-6));
}

TEST_CASE("texture: fBm and turbulence", "[texture][noise]") {
  NoiseParams one;
  one.fractal = NoiseFractal::Fbm;
  one.octaves = 1;
  NoiseParams plain;
  const Vec3f p(1.3f, -0.7f, 2.9f);
  CHECK(noise_texture(one, p) == Approx(noise_texture(plain, p)));  // one octave = the basis, mapped to [0, 1]
  CHECK(noise_texture(plain, p) == Approx(0.5f + 0.5f * perlin_noise(p)));
  NoiseParams fbm;
  fbm.fractal = NoiseFractal::Fbm;
  NoiseParams turb = fbm;
  turb.fractal = NoiseFractal::Turbulence;
  NoiseParams fbm_value = fbm;
  fbm_value.basis = NoiseBasis::Value;
  fbm_value.dims = 2;
  Pcg32 rng(3);
  double mean_fbm = 0, mean_turb = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const Vec3f q(rng.next_float() * 10, rng.next_float() * 10, rng.next_float() * 10);
    const float f = noise_texture(fbm, q), t = noise_texture(turb, q), v = noise_texture(fbm_value, q);
    REQUIRE(f >= 0);
    REQUIRE(f <= 1);
    REQUIRE(t >= 0);
    REQUIRE(t <= 1);
    REQUIRE(v >= 0);
    REQUIRE(v <= 1);
    // A 2D noise ignores z.
    REQUIRE(v == noise_texture(fbm_value, Vec3f(q.x, q.y, q.z + 5)));
    mean_fbm += f / n;
    mean_turb += t / n;
  }
  CHECK(mean_fbm == Approx(0.5).margin(0.05));  // symmetric around 0.5
  CHECK(mean_turb < 0.45);                      // |n| averages well below the maximum
  CHECK(mean_turb > 0.05);
  // More octaves add detail: fBm differs from its first octave.
  CHECK(noise_texture(fbm, p) != Approx(noise_texture(one, p)).margin(1e-4));
  // The texture wrapper matches the function, and rejects bad parameters.
  CHECK(eval_float(tx::noise(fbm), at_p(p)) == noise_texture(fbm, p));
  NoiseParams bad = fbm;
  bad.octaves = 0;
  CHECK_THROWS_AS(tx::noise(bad), Error);
  bad = fbm;
  bad.gain = 1.5f;
  CHECK_THROWS_AS(tx::noise(bad), Error);
}

TEST_CASE("texture: spherical, cylindrical and planar mappings of known points", "[texture][mapping]") {
  auto near = [](Vec2f a, Vec2f b) { return std::fabs(a.x - b.x) < 1e-5f && std::fabs(a.y - b.y) < 1e-5f; };
  CHECK(near(spherical_mapping({2, 0, 0}), {0, 0.5f}));
  CHECK(near(spherical_mapping({0, 0, 1}), {0.25f, 0.5f}));
  CHECK(near(spherical_mapping({-1, 0, 0}), {0.5f, 0.5f}));
  CHECK(near(spherical_mapping({0, 0, -3}), {0.75f, 0.5f}));
  CHECK(spherical_mapping({0, 5, 0}).y == Approx(1));   // north pole
  CHECK(spherical_mapping({0, -1, 0}).y == Approx(0));  // south pole
  CHECK(spherical_mapping({1, 1, 0}).y == Approx(0.75));
  CHECK(near(cylindrical_mapping({0, 3, 1}), {0.25f, 3}));
  CHECK(near(cylindrical_mapping({-2, -1, 0}), {0.5f, -1}));
  CHECK(near(planar_mapping({1, 2, 3}, {1, 0, 0}, {0, 0, 1}, {0.5f, 0}), {1.5f, 3}));

  // As textures with transforms: a sphere centred at (0, 10, 0).
  const TexturePtr sph = tx::spherical(translate({0, 10, 0}));
  TextureTableBuilder b;
  const int32_t i = b.add_node(sph);
  const int32_t j = b.add_node(tx::cylindrical(translate({0, 10, 0})));
  const int32_t k = b.add_node(tx::planar({0, 0, 2}, {1, 0, 0}, {0, 1}, translate({1, 0, 0})));
  const TextureTable t = b.finish();
  TexValue v = t.eval_node(i, at_p({0, 10, 4}), {});
  CHECK(v.x == Approx(0.25f));
  CHECK(v.y == Approx(0.5f));
  v = t.eval_node(j, at_p({0, 12, 4}), {});
  CHECK(v.x == Approx(0.25f));
  CHECK(v.y == Approx(2));
  v = t.eval_node(k, at_p({3, 0, 1}), {});  // mapping space (2, 0, 1): s = 2 z = 2, t = x + 1 = 3
  CHECK(v.x == Approx(2));
  CHECK(v.y == Approx(3));
}

TEST_CASE("texture: grayscale and spline colour maps", "[texture][colormap]") {
  const std::vector<Rgb> colors{{0, 0, 0}, {1, 0, 0}, {1, 1, 1}};
  const std::vector<float> pos{0, 0.5f, 1};
  for (bool linear : {false, true}) {
    INFO("linear " << linear);
    for (int k = 0; k < 3; ++k) CHECK(eval_spline(colors.data(), pos.data(), 3, linear, pos[size_t(k)]) == colors[size_t(k)]);
    CHECK(eval_spline(colors.data(), pos.data(), 3, linear, -1) == colors[0]);   // clamped
    CHECK(eval_spline(colors.data(), pos.data(), 3, linear, 7) == colors[2]);
  }
  const Rgb mid = eval_spline(colors.data(), pos.data(), 3, true, 0.25f);
  CHECK(mid.r == Approx(0.5f));
  CHECK(mid.g == 0);
  // Catmull-Rom: continuous through a knot, and never negative.
  const Rgb l = eval_spline(colors.data(), pos.data(), 3, false, 0.5f - 1e-4f);
  const Rgb r = eval_spline(colors.data(), pos.data(), 3, false, 0.5f + 1e-4f);
  CHECK(std::fabs(l.g - r.g) < 1e-3f);
  for (int i = 0; i <= 100; ++i) {
    const Rgb c = eval_spline(colors.data(), pos.data(), 3, false, float(i) / 100);
    REQUIRE(c.g >= 0);
  }
  // As textures: a spline of a scalar texture, evenly spaced positions by default.
  const TexturePtr sp = tx::spline(colors, {}, true);
  CHECK(sp->input == ValueType::Float);
  CHECK(eval_color(tx::compose(sp, tx::constant(0.75f)), {}).g == Approx(0.5f));
  CHECK(eval_color(tx::compose(tx::grayscale(), tx::constant(0.3f)), {}) == Rgb(0.3f));
  CHECK_THROWS_AS(tx::spline(colors, {0, 1}, false), Error);      // count mismatch
  CHECK_THROWS_AS(tx::spline(colors, {0, 0.5f, 0.5f}, false), Error);  // not increasing
}

TEST_CASE("texture: arithmetic with broadcasting", "[texture]") {
  const TexturePtr two = tx::constant(2.0f), col = tx::constant(Rgb(0.1f, 0.2f, 0.3f));
  const TexturePtr u = tx::checker(tx::constant(1.0f), tx::constant(3.0f), 2);  // scalar, 1 or 3
  const TextureContext c = at_uv(0.5f, 0.5f), c3 = at_uv(1.5f, 0.5f);
  CHECK(eval_float(tx::add(two, u), c) == 3);
  CHECK(eval_float(tx::multiply(u, two), c3) == 6);
  CHECK(eval_float(tx::scale(u, 0.5f), c3) == 1.5f);
  const TexturePtr sum = tx::add(col, u);  // Float broadcasts to Rgb
  CHECK(sum->output == ValueType::Rgb);
  const Rgb s = eval_color(sum, c);
  CHECK(s.r == Approx(1.1f));
  CHECK(s.b == Approx(1.3f));
  const Rgb m = eval_color(tx::multiply(u, col), c3);
  CHECK(m.g == Approx(0.6f));
  const TexturePtr t = tx::checker(tx::constant(0.0f), tx::constant(0.25f), 2);
  const TexturePtr l = tx::lerp(t, tx::constant(Rgb(0, 0, 1)), tx::constant(Rgb(4, 0, 0)));
  CHECK(eval_color(l, c) == Rgb(0, 0, 1));
  CHECK(eval_color(l, c3) == Rgb(1, 0, 0.75f));
  // A colour cannot drive lerp's t, nor feed a FloatInput.
  CHECK_THROWS_WITH(tx::lerp(col, two, two), Catch::Contains("'t' must be a scalar texture, got a colour"));
  TextureTableBuilder b;
  CHECK_THROWS_WITH(b.add(FloatInput{0, col}), Catch::Contains("expected a scalar texture, got a colour"));
  CHECK_THROWS_WITH(tx::add(tx::uv(), two), Catch::Contains("'a' must be a scalar or colour texture, got a 2D"));
}

TEST_CASE("texture: composition and its type checks", "[texture]") {
  NoiseParams np;
  np.fractal = NoiseFractal::Turbulence;
  np.octaves = 3;
  const TexturePtr noise3 = tx::noise(np);
  const TexturePtr map = tx::spline({{0, 0, 0}, {1, 0.5f, 0.25f}}, {}, true);
  const TexturePtr space = tx::xyz(torte::scale({0.5f, 0.5f, 0.5f}));
  const TexturePtr marble = tx::compose(tx::compose(map, noise3), space);
  CHECK(marble->input == ValueType::None);
  CHECK(marble->output == ValueType::Rgb);
  const Vec3f p(0.7f, 1.9f, -0.4f);
  const float expect = noise_texture(np, p * 2.0f);
  const Rgb got = eval_color(marble, at_p(p));
  CHECK(got.r == Approx(expect));
  CHECK(got.g == Approx(0.5f * expect));
  // Associativity: map o (noise o space) == (map o noise) o space.
  CHECK(eval_color(tx::compose(map, tx::compose(noise3, space)), at_p(p)) == got);
  // Uncomposed 3D noise reads the world point; 2D patterns read uv.
  CHECK(eval_float(noise3, at_p(p)) == noise_texture(np, p));
  // Errors name what was expected.
  CHECK_THROWS_WITH(tx::compose(noise3, tx::uv()),
                    Catch::Contains("takes a 3D-vector input but the inner texture (uv) gives a 2D-vector"));
  CHECK_THROWS_WITH(tx::compose(tx::uv(), tx::xyz()), Catch::Contains("takes no input"));
  CHECK_THROWS_WITH(tx::compose(map, tx::constant(Rgb(1))), Catch::Contains("gives a colour value"));
  CHECK_THROWS_WITH(tx::close(map), Catch::Contains("takes a scalar input"));
  TextureTableBuilder b;
  CHECK_THROWS_AS(b.add(ColorInput{Rgb(), map}), Error);
  // Pointwise arithmetic on patterns with different inputs is an error; with the same input it shares it.
  NoiseParams n2;
  n2.dims = 2;
  // Different pattern inputs: each operand takes its default input (3D: p, 2D: uv).
  const TexturePtr mixed = tx::add(noise3, tx::noise(n2));
  CHECK(mixed->input == ValueType::None);
  TextureContext mc = at_p(p);
  mc.uv = {0.4f, 0.8f};
  CHECK(eval_float(mixed, mc) == Approx(noise_texture(np, p) + noise_texture(n2, {0.4f, 0.8f, 0})));
  CHECK_THROWS_WITH(tx::add(map, tx::noise(n2)), Catch::Contains("'a' is a spline texture taking a scalar input"));
  CHECK_THROWS_WITH(tx::checker(tx::constant(0.0f), map, 2), Catch::Contains("'b' is a spline texture taking a scalar"));
  const TexturePtr both = tx::add(tx::noise(n2), tx::checker(tx::constant(0.0f), tx::constant(1.0f), 2));
  CHECK(both->input == ValueType::Vec2);
  const TexturePtr shifted = tx::compose(both, tx::uv({1, 1}, {1, 0}));
  n2.seed = 0;
  CHECK(eval_float(shifted, at_uv(0.25f, 0.5f)) == Approx(noise_texture(n2, {1.25f, 0.5f, 0}) + 1.0f));
}

TEST_CASE("texture: image lookups get st and a filter width from the mapping", "[texture]") {
  const TexturePtr img = tx::image(std::make_shared<CoordImage>());
  CHECK(img->input == ValueType::Vec2);
  TextureContext c = at_uv(0.25f, 0.75f);
  CHECK(eval_color(img, c) == Rgb(0.25f, 0.75f, 0));  // footprint unknown: width 0
  c.dpdu = {2, 0, 0};
  c.dpdv = {0, 0, 4};
  c.footprint = 0.1f;
  // uv width = max(0.1 / 2, 0.1 / 4) = 0.05, times the uv scale 3.
  const Rgb r = eval_color(tx::compose(img, tx::uv({3, 3})), c);
  CHECK(r.r == Approx(0.75f));
  CHECK(r.b == Approx(0.15f));
  CHECK_THROWS_AS(tx::compose(img, tx::xyz()), Error);
}

TEST_CASE("texture: flattening stores a shared subtree once", "[texture]") {
  NoiseParams np;
  np.fractal = NoiseFractal::Fbm;
  const TexturePtr shared = tx::compose(tx::noise(np), tx::xyz(torte::scale({3, 3, 3})));  // 3 nodes
  const TexturePtr a = tx::scale(shared, 2);                                                // +1
  const TexturePtr b = tx::add(shared, tx::multiply(shared, a));                            // +1 mul, +1 add
  TextureTableBuilder builder;
  const FloatParam pa = builder.add(FloatInput{0, a});
  const FloatParam pb = builder.add(FloatInput{0, b});
  const FloatParam pb2 = builder.add(FloatInput{0, b});  // the same texture again: the same root
  const ColorParam pc = builder.add(ColorInput{Rgb(), shared});
  const TextureTable table = builder.finish();
  CHECK(table.size() == 6);
  CHECK(pb2.texture == pb.texture);
  CHECK(pc.texture >= 0);
  CHECK(table.node(size_t(pc.texture)).kind == TextureKind::Compose);
  const TextureContext c = at_p({0.3f, 0.6f, 0.9f});
  const float s = table.eval(FloatParam{0, pc.texture}, c);
  CHECK(table.eval(pa, c) == Approx(2 * s));
  CHECK(table.eval(pb, c) == Approx(s + s * 2 * s));
  // Closing is deduplicated too: one uv node and one compose node for a pattern added twice.
  const TexturePtr chk = tx::checker(tx::constant(0.0f), tx::constant(1.0f), 2);
  TextureTableBuilder b2;
  const FloatParam q1 = b2.add(FloatInput{0, chk});
  const FloatParam q2 = b2.add(FloatInput{0, chk});
  CHECK(q1.texture == q2.texture);
  CHECK(b2.finish().size() == 5);  // 2 constants, checker, uv, compose
}

TEST_CASE("texture: constants take the inline fast path", "[texture]") {
  TextureTableBuilder b;
  const FloatParam f = b.add(FloatInput{0.25f, nullptr});
  const FloatParam g = b.add(FloatInput{0, tx::constant(0.5f)});  // a constant texture folds to a value
  const ColorParam c = b.add(ColorInput{Rgb(0.1f, 0.2f, 0.3f), nullptr});
  const ColorParam d = b.add(ColorInput{Rgb(), tx::constant(0.75f)});  // scalar constant as grey
  CHECK(f.texture == -1);
  CHECK(g.texture == -1);
  CHECK(g.value == 0.5f);
  CHECK(c.texture == -1);
  CHECK(d.texture == -1);
  CHECK(d.value == Rgb(0.75f));
  const TextureTable table = b.finish();
  CHECK(table.empty());  // nothing was stored: evaluation cannot touch the table
  CHECK(table.eval(f, {}) == 0.25f);
  CHECK(table.eval(g, {}) == 0.5f);
  CHECK(table.eval(c, {}) == Rgb(0.1f, 0.2f, 0.3f));
  CHECK(TextureTable().eval(d, {}) == Rgb(0.75f));
}
