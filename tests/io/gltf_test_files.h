// glTF files written by tests: a unit quad with a material, a node tree, a camera and a point light, as .gltf
// (embedded or external buffer) or .glb; and a minimal PNG writer for the textures such files embed.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace torte::test {

inline std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const uint32_t v = uint32_t(uint8_t(in[i])) << 16 | uint32_t(uint8_t(in[i + 1])) << 8 | uint8_t(in[i + 2]);
    for (int s = 18; s >= 0; s -= 6) out += k[(v >> s) & 63];
  }
  if (i < in.size()) {
    uint32_t v = uint32_t(uint8_t(in[i])) << 16;
    if (i + 1 < in.size()) v |= uint32_t(uint8_t(in[i + 1])) << 8;
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < in.size() ? k[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

template <class T>
inline void put(std::string& b, T v) {
  char c[sizeof(T)];
  std::memcpy(c, &v, sizeof v);
  b.append(c, sizeof c);
}

// A unit quad in the xy plane facing +z (positions, normals, uvs, 6 indices of `index_type`), a red material,
// a node tree (a parent scaling by 2 around the quad's node), a camera at z = 5 looking down -z (glTF's
// convention) and a point light. `uri` is the buffer's uri ("" for .glb's own chunk).
struct Gltf {
  std::string json, bin;
};
inline Gltf make(int index_type, const std::string& uri) {
  std::string b;
  for (float p : {-0.5f, -0.5f, 0.f, 0.5f, -0.5f, 0.f, 0.5f, 0.5f, 0.f, -0.5f, 0.5f, 0.f}) put(b, p);
  for (int i = 0; i < 4; ++i) put(b, 0.f), put(b, 0.f), put(b, 1.f);
  for (float t : {0.f, 1.f, 1.f, 1.f, 1.f, 0.f, 0.f, 0.f}) put(b, t);
  const size_t index_offset = b.size();
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) {
    if (index_type == 5121) put(b, uint8_t(i));
    else if (index_type == 5123) put(b, uint16_t(i));
    else put(b, i);
  }
  const size_t index_bytes = b.size() - index_offset;
  while (b.size() % 4) b += '\0';
  const std::string buffer_uri = uri.empty() ? "" : ", \"uri\": \"" + uri + "\"";
  Gltf g;
  g.bin = b;
  g.json = R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
 "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 1, 1], "intensity": 2}]}},
 "scene": 0, "scenes": [{"nodes": [0, 2, 3]}],
 "nodes": [{"scale": [2, 2, 2], "children": [1]}, {"mesh": 0, "translation": [0, 0, 0]},
           {"camera": 0, "translation": [0, 0, 5]},
           {"translation": [0, 0, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
 "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}],
 "materials": [{"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.05, 0.05, 1],
                "metallicFactor": 0, "roughnessFactor": 1}},
               {"name": "lamp", "emissiveFactor": [1, 1, 1]}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                             "material": 0}]}],
 "buffers": [{"byteLength": )" + std::to_string(b.size()) + buffer_uri + R"(}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                 {"buffer": 0, "byteOffset": 96, "byteLength": 32},
                 {"buffer": 0, "byteOffset": )" + std::to_string(index_offset) + R"(, "byteLength": )" +
           std::to_string(index_bytes) + R"(}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                "min": [-0.5, -0.5, 0], "max": [0.5, 0.5, 0]},
               {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
               {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
               {"bufferView": 3, "componentType": )" + std::to_string(index_type) + R"(, "count": 6, "type": "SCALAR"}]})";
  return g;
}

inline std::string glb(const Gltf& g) {
  std::string json = g.json;
  while (json.size() % 4) json += ' ';
  std::string out;
  put(out, uint32_t(0x46546C67));
  put(out, uint32_t(2));
  put(out, uint32_t(12 + 8 + json.size() + 8 + g.bin.size()));
  put(out, uint32_t(json.size()));
  put(out, uint32_t(0x4E4F534A));
  out += json;
  put(out, uint32_t(g.bin.size()));
  put(out, uint32_t(0x004E4942));
  out += g.bin;
  return out;
}

// An 8-bit RGB PNG of w x h pixels (rgb: 3 bytes per pixel, rows top first): zlib-compressed scanlines with
// filter 0, the chunks' CRCs from zlib.
inline std::string png_rgb(int w, int h, const std::vector<uint8_t>& rgb) {
  auto be32 = [](std::string& s, uint32_t v) {
    for (int i = 3; i >= 0; --i) s += char((v >> (8 * i)) & 255);
  };
  auto chunk = [&](std::string& out, const char* type, const std::string& data) {
    be32(out, uint32_t(data.size()));
    const std::string body = std::string(type, 4) + data;
    out += body;
    be32(out, uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
  };
  std::string raw;
  for (int y = 0; y < h; ++y) {
    raw += char(0);
    raw.append(reinterpret_cast<const char*>(rgb.data()) + size_t(y) * size_t(w) * 3, size_t(w) * 3);
  }
  uLongf n = compressBound(uLong(raw.size()));
  std::string z(n, '\0');
  compress(reinterpret_cast<Bytef*>(z.data()), &n, reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()));
  z.resize(n);
  std::string ihdr;
  be32(ihdr, uint32_t(w));
  be32(ihdr, uint32_t(h));
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, deflate, filter 0, no interlace
  std::string out("\x89PNG\r\n\x1a\n", 8);
  chunk(out, "IHDR", ihdr);
  chunk(out, "IDAT", z);
  chunk(out, "IEND", "");
  return out;
}

}  // namespace torte::test
