#include "film/image_header_check.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <vector>

namespace torte {

namespace {

// Attribute names quoted in a message: bytes outside printable ASCII as '?', so the message stays one line.
std::string printable(std::string s) {
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  return s;
}

int32_t le32(const unsigned char* b) {
  return int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24);
}

// Scanlines per compressed block, by the compression attribute's value (none, rle, zips, zip, piz, pxr24, b44,
// b44a, dwaa, dwab); unknown values count as the largest.
uint64_t lines_per_block(int compression) {
  static constexpr uint64_t kLines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
  return compression >= 0 && compression < 10 ? kLines[compression] : 256;
}

// What one part's header says about its decoding buffers.
struct Part {
  int64_t width = 0;
  int compression = 0;
  uint64_t pixel_bytes = 0;  // all channels of one pixel
  int64_t tile_width = 0, tile_height = 0;
  uint64_t decode_bytes() const {
    // A block or a tile, raw and decompressed, with every channel widened to 4 bytes at worst.
    const uint64_t pixels = tile_width > 0 ? uint64_t(tile_width) * uint64_t(tile_height)
                                           : uint64_t(std::max<int64_t>(width, 0)) * lines_per_block(compression);
    return pixels * pixel_bytes * 2;
  }
};

uint32_t be32(const unsigned char* b) {
  return uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | uint32_t(b[3]);
}

// PNG: length (big-endian, at most 2^31 - 1), type, data, CRC per chunk, up to IEND.
ImageHeaderCheck check_png_chunks(std::ifstream& in, int64_t size) {
  const std::string corrupt = "corrupt PNG file: ";
  int64_t at = 8;
  while (at < size) {
    unsigned char b[8];
    in.seekg(at);
    if (!in.read(reinterpret_cast<char*>(b), 8)) return {corrupt + "the file ends inside a chunk header"};
    const uint32_t length = be32(b);
    const std::string type = printable(std::string(reinterpret_cast<const char*>(b + 4), 4));
    if (type == "IEND") return {};
    const int64_t left = size - at - 12;
    if (length > 0x7fffffffu || int64_t(length) > left) {
      if (type == "IDAT") return {};  // cut pixel data: libpng reads it in pieces and reports the truncation
      return {corrupt + "chunk '" + type + "' claims " + std::to_string(length) + " bytes, " +
              std::to_string(std::max<int64_t>(left, 0)) + " are left in the file"};
    }
    at += 12 + int64_t(length);
  }
  return {};
}

ImageHeaderCheck check_exr_header(std::ifstream& in, int64_t size, const unsigned char* head) {
  ImageHeaderCheck out;
  in.seekg(8);
  const bool multipart = head[5] & 0x10;  // bit 12 of the little-endian version field
  // A null-terminated string of at most 255 characters (the limit with long names); false if it is not.
  const auto read_name = [&](std::string& s) {
    s.clear();
    for (char c; in.get(c);) {
      if (c == '\0') return true;
      if (s.size() == 255) return false;
      s += c;
    }
    return false;
  };
  const std::string corrupt = "corrupt OpenEXR header: ";
  std::string name, type;
  std::vector<unsigned char> value;
  for (;;) {
    Part part;
    for (;;) {
      if (!read_name(name)) return {corrupt + "an attribute name is unterminated or longer than 255 bytes"};
      if (name.empty()) break;  // the end of this header
      if (!read_name(type)) return {corrupt + "the type of attribute '" + printable(name) + "' is unterminated"};
      unsigned char b[4];
      if (!in.read(reinterpret_cast<char*>(b), 4)) return {corrupt + "the file ends in attribute '" + printable(name) + "'"};
      const int32_t value_size = le32(b);
      const int64_t at = int64_t(in.tellg());
      if (value_size < 0 || at + value_size > size)
        return {corrupt + "attribute '" + printable(name) + "' (" + printable(type) + ") claims " +
                std::to_string(value_size) + " bytes, " + std::to_string(size - at) + " are left in the file"};
      // The few attributes that size the decoding buffers are read; the others skipped.
      const bool wanted = (name == "dataWindow" && type == "box2i" && value_size == 16) ||
                          (name == "compression" && value_size == 1) ||
                          (name == "tiles" && type == "tiledesc" && value_size == 9) ||
                          (name == "channels" && type == "chlist");
      if (!wanted) {
        in.seekg(value_size, std::ios::cur);
        continue;
      }
      value.resize(size_t(value_size));
      if (!in.read(reinterpret_cast<char*>(value.data()), value_size)) return {corrupt + "the file ends in '" + name + "'"};
      if (name == "dataWindow") {
        part.width = int64_t(le32(&value[8])) - int64_t(le32(&value[0])) + 1;
      } else if (name == "compression") {
        part.compression = value[0];
      } else if (name == "tiles") {
        part.tile_width = uint32_t(le32(&value[0]));
        part.tile_height = uint32_t(le32(&value[4]));
      } else {  // channels: name\0, int32 pixel type (0 uint, 1 half, 2 float), 12 more bytes; a final \0
        for (size_t i = 0; i < value.size() && value[i] != 0;) {
          const unsigned char* end = static_cast<const unsigned char*>(std::memchr(&value[i], 0, value.size() - i));
          if (!end || size_t(end - value.data()) + 17 > value.size()) break;
          const size_t type_at = size_t(end - value.data()) + 1;
          part.pixel_bytes += le32(&value[type_at]) == 1 ? 2 : 4;
          i = type_at + 16;
        }
      }
    }
    out.decode_bytes = std::max(out.decode_bytes, part.decode_bytes());
    // Single-part files have one header; multi-part ones end their list of headers with an empty one.
    if (!multipart) return out;
    const int next = in.peek();
    if (next == std::char_traits<char>::eof()) return {corrupt + "the file ends in the list of part headers"};
    if (next == 0) return out;
  }
}

}  // namespace

ImageHeaderCheck check_image_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char head[8];
  if (!in.read(reinterpret_cast<char*>(head), 8)) return {};
  in.seekg(0, std::ios::end);
  const int64_t size = int64_t(in.tellg());
  if (head[0] == 0x76 && head[1] == 0x2f && head[2] == 0x31 && head[3] == 0x01) return check_exr_header(in, size, head);
  static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (std::memcmp(head, kPng, 8) == 0) return check_png_chunks(in, size);
  return {};
}

}  // namespace torte
