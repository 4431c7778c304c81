// TextureDesc constructors with their type checks, and flattening into a TextureTable.
#include "texture/texture.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <utility>

#include "core/error.h"

namespace torte {

const char* value_type_name(ValueType t) {
  switch (t) {
    case ValueType::None: return "no";
    case ValueType::Float: return "scalar";
    case ValueType::Vec2: return "2D-vector";
    case ValueType::Vec3: return "3D-vector";
    case ValueType::Rgb: return "colour";
  }
  return "?";
}

const char* texture_kind_name(TextureKind k) {
  switch (k) {
    case TextureKind::Constant: return "constant";
    case TextureKind::Uv: return "uv";
    case TextureKind::Spherical: return "spherical";
    case TextureKind::Cylindrical: return "cylindrical";
    case TextureKind::Planar: return "planar";
    case TextureKind::Xyz: return "xyz";
    case TextureKind::Checker2: return "checker";
    case TextureKind::Checker3: return "checker3d";
    case TextureKind::Noise: return "noise";
    case TextureKind::Image: return "image";
    case TextureKind::Grayscale: return "grayscale";
    case TextureKind::Spline: return "spline";
    case TextureKind::Add: return "add";
    case TextureKind::Multiply: return "multiply";
    case TextureKind::Scale: return "scale";
    case TextureKind::Lerp: return "lerp";
    case TextureKind::Compose: return "compose";
  }
  return "?";
}

namespace texture {

namespace {

std::shared_ptr<TextureDesc> node(TextureKind kind, ValueType output, ValueType input) {
  auto d = std::make_shared<TextureDesc>();
  d->kind = kind;
  d->output = output;
  d->input = input;
  return d;
}

// Sets d's depth and visit count from its children (visits: `pick_one` for a checker, which evaluates one of
// them) and refuses expressions past the limits.
// Closing a finished root (`checked` false) may add one level past the limits.
TexturePtr sealed(std::shared_ptr<TextureDesc> d, bool pick_one = false, bool checked = true) {
  uint32_t depth = 0;
  uint64_t visits = 0;
  for (const TexturePtr& c : d->children) {
    depth = std::max(depth, c->depth);
    visits = pick_one ? std::max(visits, c->visits) : visits + c->visits;  // each <= 2^16: no overflow
  }
  d->depth = depth + 1;
  d->visits = visits + 1;
  if (!checked) return d;
  if (d->depth > kMaxTextureDepth)
    throw Error("the texture expression nests " + std::to_string(d->depth) + " levels deep; the limit is " +
                std::to_string(kMaxTextureDepth) + " (combine long sums as a balanced tree)");
  if (d->visits > kMaxTextureVisits)
    throw Error("evaluating the texture expression would visit " + std::to_string(d->visits) +
                " nodes per lookup (a shared sub-texture counts once per use); the limit is " +
                std::to_string(kMaxTextureVisits));
  return d;
}

void require_invertible(const Transform& t) {
  const float det = t.determinant3();
  if (!std::isfinite(det) || std::fabs(det) < 1e-30f || !is_finite(t.inverse().apply_point(Vec3f(0, 0, 0))))
    throw Error("'transform' must be invertible (it is singular or not finite)");
}

void require(const TexturePtr& t, const char* name) {
  if (!t) throw Error(std::string("'") + name + "' is missing");
}

// A Float or Rgb texture, for arithmetic and checker colours.
void require_value(const TexturePtr& t, const char* name) {
  require(t, name);
  if (t->output != ValueType::Float && t->output != ValueType::Rgb)
    throw Error(std::string("'") + name + "' must be a scalar or colour texture, got a " +
                value_type_name(t->output) + " texture");
}

// Pointwise children share the node's input when their inputs agree (None fits anything); when they differ
// (a 2D and a 3D pattern), each child is closed (takes its own default input) and the node reads only the hit.
// Returns the node's input.
// close() for an argument: the error names it.
TexturePtr close_arg(TexturePtr t, const char* name) {
  if (t->input == ValueType::Float)
    throw Error(std::string("'") + name + "' is a " + texture_kind_name(t->kind) +
                " texture taking a scalar input, which it cannot get here; compose it with a scalar texture first "
                "(map .. noise)");
  return close(std::move(t));
}

ValueType share_inputs(std::initializer_list<std::pair<TexturePtr*, const char*>> children) {
  ValueType shared = ValueType::None;
  bool agree = true;
  for (auto [c, name] : children) {
    const ValueType in = (*c)->input;
    if (in == ValueType::None) continue;
    if (shared == ValueType::None) shared = in;
    else if (shared != in) agree = false;
  }
  if (agree) return shared;
  for (auto [c, name] : children) *c = close_arg(std::move(*c), name);
  return ValueType::None;
}

ValueType wider(ValueType a, ValueType b) { return a == ValueType::Rgb || b == ValueType::Rgb ? ValueType::Rgb : a; }

void require_finite(float v, const char* what) {
  if (!std::isfinite(v)) throw Error(std::string("'") + what + "' must be finite");
}

const TexturePtr& default_uv() {
  static const TexturePtr t = uv();
  return t;
}
const TexturePtr& default_xyz() {
  static const TexturePtr t = xyz();
  return t;
}

}  // namespace

TexturePtr constant(float value) {
  require_finite(value, "value");
  auto d = node(TextureKind::Constant, ValueType::Float, ValueType::None);
  d->value = Rgb(value);
  return d;
}

TexturePtr constant(Rgb value) {
  if (!value.is_finite()) throw Error("'value' must be finite");
  auto d = node(TextureKind::Constant, ValueType::Rgb, ValueType::None);
  d->value = value;
  return d;
}

TexturePtr uv(Vec2f scale, Vec2f offset) {
  require_finite(scale.x, "scale");
  require_finite(scale.y, "scale");
  require_finite(offset.x, "offset");
  require_finite(offset.y, "offset");
  auto d = node(TextureKind::Uv, ValueType::Vec2, ValueType::None);
  d->scale = scale;
  d->offset = offset;
  return d;
}

TexturePtr spherical(const Transform& transform) {
  require_invertible(transform);
  auto d = node(TextureKind::Spherical, ValueType::Vec2, ValueType::None);
  d->transform = transform;
  return d;
}

TexturePtr cylindrical(const Transform& transform) {
  require_invertible(transform);
  auto d = node(TextureKind::Cylindrical, ValueType::Vec2, ValueType::None);
  d->transform = transform;
  return d;
}

TexturePtr planar(Vec3f s_axis, Vec3f t_axis, Vec2f offset, const Transform& transform) {
  if (!is_finite(s_axis) || length_squared(s_axis) == 0) throw Error("'s' must be a finite non-zero vector");
  if (!is_finite(t_axis) || length_squared(t_axis) == 0) throw Error("'t' must be a finite non-zero vector");
  require_finite(offset.x, "offset");
  require_finite(offset.y, "offset");
  require_invertible(transform);
  auto d = node(TextureKind::Planar, ValueType::Vec2, ValueType::None);
  d->s_axis = s_axis;
  d->t_axis = t_axis;
  d->offset = offset;
  d->transform = transform;
  return d;
}

TexturePtr xyz(const Transform& transform) {
  require_invertible(transform);
  auto d = node(TextureKind::Xyz, ValueType::Vec3, ValueType::None);
  d->transform = transform;
  return d;
}

TexturePtr checker(TexturePtr a, TexturePtr b, int dims, float scale) {
  if (dims != 2 && dims != 3) throw Error("'dims' must be 2 or 3, got " + std::to_string(dims));
  require_value(a, "a");
  require_value(b, "b");
  require_finite(scale, "scale");
  auto d = node(dims == 2 ? TextureKind::Checker2 : TextureKind::Checker3, wider(a->output, b->output),
                dims == 2 ? ValueType::Vec2 : ValueType::Vec3);
  d->children = {close_arg(std::move(a), "a"), close_arg(std::move(b), "b")};
  d->scale = {scale, scale};
  return sealed(std::move(d), true);
}

TexturePtr noise(const NoiseParams& params) {
  if (params.dims != 2 && params.dims != 3) throw Error("'dims' must be 2 or 3, got " + std::to_string(params.dims));
  if (params.octaves < 1 || params.octaves > 16)
    throw Error("'octaves' must be between 1 and 16, got " + std::to_string(params.octaves));
  if (!(params.lacunarity > 0) || !std::isfinite(params.lacunarity)) throw Error("'lacunarity' must be positive");
  if (!(params.gain > 0 && params.gain <= 1)) throw Error("'gain' must be in (0, 1]");
  auto d = node(TextureKind::Noise, ValueType::Float, params.dims == 2 ? ValueType::Vec2 : ValueType::Vec3);
  d->noise = params;
  return d;
}

TexturePtr image(std::shared_ptr<const ImageSource> image) {
  if (!image) throw Error("'file' is missing");
  auto d = node(TextureKind::Image, ValueType::Rgb, ValueType::Vec2);
  d->image = std::move(image);
  return d;
}

TexturePtr image_scalar(std::shared_ptr<const ImageSource> image) {
  if (!image) throw Error("'file' is missing");
  auto d = node(TextureKind::Image, ValueType::Float, ValueType::Vec2);
  d->image = std::move(image);
  return d;
}

TexturePtr grayscale() { return node(TextureKind::Grayscale, ValueType::Rgb, ValueType::Float); }

TexturePtr spline(std::vector<Rgb> colors, std::vector<float> positions, bool linear) {
  if (colors.empty()) throw Error("'colors' needs at least one colour");
  for (const Rgb& c : colors)
    if (!c.is_finite()) throw Error("'colors' must be finite");
  if (positions.empty()) {
    for (size_t i = 0; i < colors.size(); ++i)
      positions.push_back(colors.size() == 1 ? 0.0f : float(i) / float(colors.size() - 1));
  } else {
    if (positions.size() != colors.size())
      throw Error("'positions' has " + std::to_string(positions.size()) + " entries but 'colors' has " +
                  std::to_string(colors.size()));
    for (size_t i = 0; i < positions.size(); ++i) {
      if (!std::isfinite(positions[i])) throw Error("'positions' must be finite");
      if (i > 0 && !(positions[i] > positions[i - 1])) throw Error("'positions' must be strictly increasing");
    }
  }
  auto d = node(TextureKind::Spline, ValueType::Rgb, ValueType::Float);
  d->colors = std::move(colors);
  d->positions = std::move(positions);
  d->linear = linear;
  return d;
}

namespace {
TexturePtr binary(TextureKind kind, TexturePtr a, TexturePtr b) {
  require_value(a, "a");
  require_value(b, "b");
  const ValueType input = share_inputs({{&a, "a"}, {&b, "b"}});
  auto d = node(kind, wider(a->output, b->output), input);
  d->children = {std::move(a), std::move(b)};
  return sealed(std::move(d));
}
}  // namespace

TexturePtr add(TexturePtr a, TexturePtr b) { return binary(TextureKind::Add, std::move(a), std::move(b)); }
TexturePtr multiply(TexturePtr a, TexturePtr b) {
  return binary(TextureKind::Multiply, std::move(a), std::move(b));
}

TexturePtr scale(TexturePtr a, float factor) {
  require_value(a, "a");
  require_finite(factor, "factor");
  auto d = node(TextureKind::Scale, a->output, a->input);
  d->factor = factor;
  d->children = {std::move(a)};
  return sealed(std::move(d));
}

TexturePtr lerp(TexturePtr t, TexturePtr a, TexturePtr b) {
  require(t, "t");
  if (t->output != ValueType::Float)
    throw Error(std::string("'t' must be a scalar texture, got a ") + value_type_name(t->output) + " texture");
  require_value(a, "a");
  require_value(b, "b");
  const ValueType input = share_inputs({{&t, "t"}, {&a, "a"}, {&b, "b"}});
  auto d = node(TextureKind::Lerp, wider(a->output, b->output), input);
  d->children = {std::move(t), std::move(a), std::move(b)};
  return sealed(std::move(d));
}

namespace {
TexturePtr compose_checked(TexturePtr outer, TexturePtr inner, bool checked) {
  require(outer, "outer");
  require(inner, "inner");
  if (outer->input == ValueType::None)
    throw Error(std::string("the outer texture (") + texture_kind_name(outer->kind) +
                ") takes no input, so nothing can be composed into it");
  if (inner->output != outer->input)
    throw Error(std::string("the outer texture (") + texture_kind_name(outer->kind) + ") takes a " +
                value_type_name(outer->input) + " input but the inner texture (" + texture_kind_name(inner->kind) +
                ") gives a " + value_type_name(inner->output) + " value");
  auto d = node(TextureKind::Compose, outer->output, inner->input);
  d->children = {std::move(outer), std::move(inner)};
  return sealed(std::move(d), false, checked);
}
}  // namespace

TexturePtr compose(TexturePtr outer, TexturePtr inner) { return compose_checked(std::move(outer), std::move(inner), true); }

TexturePtr close(TexturePtr t) {
  require(t, "texture");
  switch (t->input) {
    case ValueType::None: return t;
    case ValueType::Vec2: return compose_checked(std::move(t), default_uv(), false);
    case ValueType::Vec3: return compose_checked(std::move(t), default_xyz(), false);
    default:
      throw Error(std::string("a ") + texture_kind_name(t->kind) + " texture takes a " +
                  value_type_name(t->input) + " input and cannot be used on its own; compose it with a " +
                  value_type_name(t->input) + " texture (map .. texture)");
  }
}

}  // namespace texture

// ---- flattening --------------------------------------------------------------------------------------------

TexturePtr TextureTableBuilder::closed(const TexturePtr& t) {
  if (t->input == ValueType::None) return t;
  auto it = closed_.find(t.get());
  if (it != closed_.end()) return it->second;
  TexturePtr c = texture::close(t);
  closed_.emplace(t.get(), c);
  return c;
}

FloatParam TextureTableBuilder::add(const FloatInput& input) {
  if (!input.texture) return {input.value, -1};
  const TexturePtr& t = input.texture;
  if (t->output != ValueType::Float)
    throw Error(std::string("expected a scalar texture, got a ") + value_type_name(t->output) + " texture");
  if (t->kind == TextureKind::Constant) return {t->value.r, -1};
  return {0, add_node(closed(t))};
}

ColorParam TextureTableBuilder::add(const ColorInput& input) {
  if (!input.texture) return {input.value, -1};
  const TexturePtr& t = input.texture;
  if (t->output != ValueType::Float && t->output != ValueType::Rgb)
    throw Error(std::string("expected a colour or scalar texture, got a ") + value_type_name(t->output) +
                " texture");
  if (t->kind == TextureKind::Constant) return {t->value, -1};
  return {Rgb(), add_node(closed(t))};
}

int32_t TextureTableBuilder::add_node(const TexturePtr& t) {
  if (!t) throw Error("TextureTableBuilder::add_node: null texture");
  keep_.push_back(t);
  return flatten(*t);
}

int32_t TextureTableBuilder::flatten(const TextureDesc& d) {
  if (auto it = index_.find(&d); it != index_.end()) return it->second;
  TextureNode n;
  n.kind = d.kind;
  n.output = d.output;
  int32_t child[3] = {-1, -1, -1};
  for (size_t i = 0; i < d.children.size() && i < 3; ++i) child[i] = flatten(*d.children[i]);
  n.a = child[0];
  n.b = child[1];
  n.c = child[2];
  auto& tb = table_;
  switch (d.kind) {
    case TextureKind::Constant:
      n.f[0] = d.value.r, n.f[1] = d.value.g, n.f[2] = d.value.b;
      break;
    case TextureKind::Uv:
      n.f[0] = d.scale.x, n.f[1] = d.scale.y, n.f[2] = d.offset.x, n.f[3] = d.offset.y;
      n.width_scale = std::max(std::fabs(d.scale.x), std::fabs(d.scale.y));
      break;
    case TextureKind::Planar:
      n.f[0] = d.s_axis.x, n.f[1] = d.s_axis.y, n.f[2] = d.s_axis.z;
      n.f[3] = d.t_axis.x, n.f[4] = d.t_axis.y, n.f[5] = d.t_axis.z;
      n.f[6] = d.offset.x, n.f[7] = d.offset.y;
      [[fallthrough]];
    case TextureKind::Spherical:
    case TextureKind::Cylindrical:
    case TextureKind::Xyz: {
      n.extra = int32_t(tb.transforms_.size());
      tb.transforms_.push_back(d.transform);
      // World -> mapping space scales lengths by about the cube root of |det| of the inverse.
      n.width_scale = std::cbrt(std::fabs(d.transform.inverse().determinant3()));
      if (d.kind == TextureKind::Planar) n.width_scale *= std::max(length(d.s_axis), length(d.t_axis));
      break;
    }
    case TextureKind::Checker2:
    case TextureKind::Checker3:
      n.f[0] = d.scale.x;
      break;
    case TextureKind::Noise:
      n.noise = d.noise;
      break;
    case TextureKind::Image:
      n.extra = int32_t(tb.images_.size());
      tb.images_.push_back(d.image);
      break;
    case TextureKind::Spline:
      n.extra = int32_t(tb.knot_colors_.size());
      n.count = int32_t(d.colors.size());
      n.flag = d.linear ? 1 : 0;
      tb.knot_colors_.insert(tb.knot_colors_.end(), d.colors.begin(), d.colors.end());
      tb.knot_positions_.insert(tb.knot_positions_.end(), d.positions.begin(), d.positions.end());
      break;
    case TextureKind::Scale:
      n.f[0] = d.factor;
      break;
    case TextureKind::Grayscale:
    case TextureKind::Add:
    case TextureKind::Multiply:
    case TextureKind::Lerp:
    case TextureKind::Compose:
      break;
  }
  const int32_t index = int32_t(tb.nodes_.size());
  tb.nodes_.push_back(n);
  index_.emplace(&d, index);
  return index;
}

TextureTable TextureTableBuilder::finish() {
  TextureTable t = std::move(table_);
  table_ = TextureTable();
  index_.clear();
  closed_.clear();
  keep_.clear();
  return t;
}

}  // namespace torte
