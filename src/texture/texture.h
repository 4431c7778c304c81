// Composable, functional textures (after dort): a texture is a typed function
//     input -> output,   input in {none (reads only the hit), Float, Vec2, Vec3},  output in {Float, Vec2, Vec3, Rgb}.
//
//   * mappings (uv, spherical, cylindrical, planar -> Vec2; xyz -> Vec3) read the hit (input none);
//   * patterns take Vec2 (checker 2D, 2D noise, image) or Vec3 (checker 3D, 3D noise) and give Float or Rgb;
//   * colour maps (grayscale, spline) take a Float and give Rgb;
//   * arithmetic (add, multiply, scale, lerp) combines Float/Rgb textures pointwise: children share the node's
//     input, a Float broadcasts to Rgb, constants fit any input;
//   * compose(f, g) = f o g needs g's output type == f's input type.
// A texture used as a material parameter (or as a checker's colour) is "closed" first: a Vec2-input texture
// is composed with uv(), a Vec3-input one with xyz() (the world point); a Float-input one is an error.
//
// Two representations, like materials:
//   * builder side: immutable TextureDesc nodes linked by shared_ptr, made by the functions in
//     torte::texture (type-checked on construction: they throw torte::Error naming the argument);
//   * scene side: TextureTable, a flat vector of POD nodes referencing children by index, evaluated by a switch
//     on the node kind; TextureTableBuilder flattens descs into it, storing a shared sub-texture once.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/rgb.h"
#include "core/transform.h"
#include "core/vec.h"
#include "texture/image_texture.h"
#include "texture/noise.h"
#include "texture/texture_param.h"

namespace torte {

// What a texture sees of a shading point.
struct TextureContext {
  Vec3f p;           // world-space position
  Vec3f n;           // world-space shading normal
  Vec2f uv;          // surface parameterisation
  Vec3f dpdu, dpdv;  // world-space partial derivatives of p (0 when unknown)
  float footprint = 0;  // world-space radius of the pixel footprint; 0 = unknown -> finest MIP level
};

enum class ValueType : uint8_t { None, Float, Vec2, Vec3, Rgb };  // None: as an input, "reads only the hit"
const char* value_type_name(ValueType t);  // "scalar", "2D-vector", "3D-vector", "colour", "no"

enum class TextureKind : uint8_t {
  Constant,
  Uv, Spherical, Cylindrical, Planar, Xyz,                  // mappings
  Checker2, Checker3, Noise, Image,                          // patterns
  Grayscale, Spline,                                         // colour maps
  Add, Multiply, Scale, Lerp,                                // arithmetic
  Compose,
};
const char* texture_kind_name(TextureKind k);

// Builder-side node. Children: Add/Multiply (a, b), Scale (a), Lerp (t, a, b), Checker (a, b) (closed),
// Compose (outer, inner).
struct TextureDesc {
  TextureKind kind = TextureKind::Constant;
  ValueType output = ValueType::Float;
  ValueType input = ValueType::None;
  std::vector<std::shared_ptr<const TextureDesc>> children;
  Rgb value;                  // Constant (a Float constant has r = g = b)
  Vec2f scale{1, 1}, offset;  // Uv: uv * scale + offset; Planar: offset; Checker: scale.x = frequency
  Vec3f s_axis{1, 0, 0}, t_axis{0, 1, 0};  // Planar
  Transform transform;        // Spherical, Cylindrical, Planar, Xyz: places the mapping in the world
  float factor = 1;           // Scale
  NoiseParams noise;          // Noise
  std::vector<Rgb> colors;    // Spline
  std::vector<float> positions;
  bool linear = false;
  std::shared_ptr<const ImageSource> image;  // Image
  // Set by the constructors below: the longest chain of nodes down to a leaf (1 for a leaf), and how many nodes
  // one evaluation visits (a shared sub-texture counts once per use; a checker visits one of its colours).
  uint32_t depth = 1;
  uint64_t visits = 1;
};
using TexturePtr = std::shared_ptr<const TextureDesc>;

/// Texture expressions nest at most kMaxTextureDepth levels and one evaluation visits at most kMaxTextureVisits
/// nodes: the constructors refuse more (torte::Error), so flattening, evaluation at render time (recursive, on
/// render threads' stacks) and destruction of the shared graph stay bounded in stack and time.
constexpr uint32_t kMaxTextureDepth = 1024;
constexpr uint64_t kMaxTextureVisits = uint64_t(1) << 16;

// Constructors. Each validates its arguments and throws torte::Error("'<argument>' ...") on a type error, and
// torte::Error when the result would pass kMaxTextureDepth or kMaxTextureVisits. Mapping transforms must be
// invertible.
namespace texture {
TexturePtr constant(float value);
TexturePtr constant(Rgb value);
TexturePtr uv(Vec2f scale = {1, 1}, Vec2f offset = {0, 0});
TexturePtr spherical(const Transform& transform = {});
TexturePtr cylindrical(const Transform& transform = {});
TexturePtr planar(Vec3f s_axis = {1, 0, 0}, Vec3f t_axis = {0, 1, 0}, Vec2f offset = {0, 0},
                  const Transform& transform = {});
TexturePtr xyz(const Transform& transform = {});  // the world point, in the space placed by `transform`
// Alternates a and b (Float or Rgb; closed) over unit cells of (scale * input): 2D cells of a Vec2, 3D of a Vec3.
// The cell with floor(x) + floor(y) (+ floor(z)) even is a.
TexturePtr checker(TexturePtr a, TexturePtr b, int dims, float scale = 1);
TexturePtr noise(const NoiseParams& params);  // input Vec2 or Vec3 by params.dims; Float in [0, 1]
TexturePtr image(std::shared_ptr<const ImageSource> image);  // Vec2 (st) -> Rgb
// Vec2 (st) -> Float: the image's first channel (height and mask maps, which are grey).
TexturePtr image_scalar(std::shared_ptr<const ImageSource> image);
TexturePtr grayscale();  // Float -> Rgb (r = g = b = x)
// Float -> Rgb; positions empty = evenly spaced over [0, 1]. Needs >= 1 colour (>= 2 for positions).
TexturePtr spline(std::vector<Rgb> colors, std::vector<float> positions, bool linear);
TexturePtr add(TexturePtr a, TexturePtr b);
TexturePtr multiply(TexturePtr a, TexturePtr b);
TexturePtr scale(TexturePtr a, float factor);
TexturePtr lerp(TexturePtr t, TexturePtr a, TexturePtr b);  // (1 - t) a + t b; t a Float texture
TexturePtr compose(TexturePtr outer, TexturePtr inner);     // outer o inner
// The texture with its default input supplied (itself when it reads only the hit). Throws for Float input. The
// closed texture may pass kMaxTextureDepth by the one level it adds.
TexturePtr close(TexturePtr t);
}  // namespace texture

// ---- scene side --------------------------------------------------------------------------------------------
// A texture value: Float results are splatted (x = y = z), Vec2 leave z = 0, so a Float broadcasts to Rgb for
// free. `width`: the lookup footprint in the value's own units (set by mappings, used by image lookups).
struct TexValue {
  float x = 0, y = 0, z = 0;
  float width = 0;
};

struct TextureNode {
  TextureKind kind = TextureKind::Constant;
  ValueType output = ValueType::Float;
  uint8_t flag = 0;              // Spline: linear; Checker: unused
  int32_t a = -1, b = -1, c = -1;  // children (node indices)
  int32_t extra = -1;            // index into transforms / images / spline knots
  int32_t count = 0;             // Spline: knot count
  float f[8] = {};               // kind-specific parameters (see TextureTableBuilder::flatten)
  float width_scale = 1;         // mappings: footprint (world units) -> footprint in the mapping's units
  NoiseParams noise;
};

class TextureTable {
 public:
  float eval(const FloatParam& p, const TextureContext& ctx) const {
    if (p.texture < 0) return p.value;
    return eval_node(p.texture, ctx, TexValue{}).x;
  }
  Rgb eval(const ColorParam& p, const TextureContext& ctx) const {
    if (p.texture < 0) return p.value;
    const TexValue v = eval_node(p.texture, ctx, TexValue{});
    return {v.x, v.y, v.z};
  }
  // Node `index` applied to `input` (ignored by nodes that read only the hit).
  TexValue eval_node(int32_t index, const TextureContext& ctx, TexValue input) const;

  size_t size() const { return nodes_.size(); }
  const TextureNode& node(size_t i) const { return nodes_[i]; }
  bool empty() const { return nodes_.empty(); }
  // The image sources the nodes look up (the renderer checks their failure()).
  const std::vector<std::shared_ptr<const ImageSource>>& images() const { return images_; }

 private:
  friend class TextureTableBuilder;
  std::vector<TextureNode> nodes_;
  std::vector<Transform> transforms_;  // the nodes' mapping transforms (their inverses are applied)
  std::vector<std::shared_ptr<const ImageSource>> images_;
  std::vector<Rgb> knot_colors_;
  std::vector<float> knot_positions_;
};

class TextureTableBuilder {
 public:
  // A constant (no texture, or a constant texture) becomes an inline parameter; otherwise the texture is
  // closed, flattened (once per distinct TextureDesc) and the parameter refers to its root.
  // Throws torte::Error if the texture's output does not fit (a colour for a FloatInput, vectors for either).
  FloatParam add(const FloatInput& input);
  ColorParam add(const ColorInput& input);
  // Flattens `t` as is (no closing) and returns its root's index.
  int32_t add_node(const TexturePtr& t);
  TextureTable finish();

 private:
  int32_t flatten(const TextureDesc& d);
  TexturePtr closed(const TexturePtr& t);
  TextureTable table_;
  std::unordered_map<const TextureDesc*, int32_t> index_;
  std::unordered_map<const TextureDesc*, TexturePtr> closed_;  // roots closed here
  std::vector<TexturePtr> keep_;  // every flattened root stays alive, so the pointers in index_ stay unique
};

}  // namespace torte
