// Texture-or-constant parameters that materials hold.
//
// Builder side (MaterialDesc): FloatInput / ColorInput keep a constant and, optionally, a texture graph made by
// torte.texture.* (an immutable TextureDesc shared between materials). Scene side (flattened materials):
// FloatParam / ColorParam keep the constant inline, or the index of the texture's root node in the scene's
// TextureTable (see texture/texture.h: TextureTableBuilder::add turns an Input into a Param, and
// TextureTable::eval evaluates a Param, taking an inlined fast path when it is a constant).
#pragma once
#include <cstdint>
#include <memory>

#include "core/rgb.h"

namespace torte {

struct TextureDesc;

// ---- builder side ------------------------------------------------------------------------------------------
struct FloatInput {
  float value = 0;                             // used when texture is null
  std::shared_ptr<const TextureDesc> texture;  // a Float-valued texture, or null
};
struct ColorInput {
  Rgb value;                                   // used when texture is null
  std::shared_ptr<const TextureDesc> texture;  // an Rgb- or Float-valued texture (Float is broadcast), or null
};

// ---- scene side --------------------------------------------------------------------------------------------
struct FloatParam {
  float value = 0;
  int32_t texture = -1;  // -1: the constant `value`; else a node index in the TextureTable
};
struct ColorParam {
  Rgb value;
  int32_t texture = -1;
};

}  // namespace torte
