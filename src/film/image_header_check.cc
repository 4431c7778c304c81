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

// The largest factor by which decode_bytes() can exceed a block's stored bytes: the compression's largest ratio of
// decoded to stored size, times 4 (decode_bytes counts the stored and the decoded buffer, and a margin of 2). The
// ratios: none 1, RLE 64 (a 2-byte run of 128), zlib-based (ZIPS, ZIP, PXR24) 1032, PIZ 4096 (Huffman runs), B44
// 2.3 and B44A 11 (4x4 blocks of 32 bytes in 14 or 3).
// DWAA, DWAB and unknown values (whose ratio has no simple bound) are left to the memory budget alone.
uint64_t max_expansion(int compression) {
  static constexpr uint64_t kExpansion[] = {1, 64, 1032, 1032, 4096, 1032, 3, 11};
  return 4 * (compression >= 0 && compression < 8 ? kExpansion[compression] : uint64_t(1) << 40);
}

// The value size of OpenEXR's fixed-size attribute types, or -1 for the variable-size ones and unknown types.
int64_t fixed_value_size(const std::string& type) {
  static const std::pair<const char*, int64_t> kSizes[] = {
      {"box2i", 16},   {"box2f", 16},   {"chromaticities", 32}, {"compression", 1}, {"double", 8},
      {"envmap", 1},   {"float", 4},    {"int", 4},             {"keycode", 28},    {"lineOrder", 1},
      {"m33f", 36},    {"m33d", 72},    {"m44f", 64},           {"m44d", 128},      {"rational", 8},
      {"tiledesc", 9}, {"timecode", 8}, {"v2i", 8},             {"v2f", 8},         {"v2d", 16},
      {"v3i", 12},     {"v3f", 12},     {"v3d", 24},            {"deepImageState", 1}};
  for (const auto& [name, bytes] : kSizes)
    if (type == name) return bytes;
  return -1;
}

// A channel list as OpenEXR reads it (entries of name\0, int32 pixel type (0 uint, 1 half, 2 float), pLinear and 3
// reserved bytes, int32 x and y sampling, up to an empty name): "" when its final \0 is the value's last byte and
// every entry is valid, else what is wrong. Adds each channel's bytes to `*pixel_bytes` when given. OpenImageIO
// 2.4 aborts the process on a pixel type it does not know (a fuzzed EXR's channel of type 240766).
std::string channel_list_problem(const std::vector<unsigned char>& value, uint64_t* pixel_bytes) {
  size_t i = 0;
  while (i < value.size() && value[i] != 0) {
    const void* end = std::memchr(&value[i], 0, value.size() - i);
    const size_t type_at = end ? size_t(static_cast<const unsigned char*>(end) - value.data()) + 1 : value.size();
    if (type_at + 16 > value.size()) break;
    const std::string channel = printable(std::string(reinterpret_cast<const char*>(&value[i]), type_at - 1 - i));
    const int32_t type = le32(&value[type_at]);
    if (type < 0 || type > 2)
      return "channel '" + channel + "' has pixel type " + std::to_string(type) + " (0 uint, 1 half, 2 float)";
    if (le32(&value[type_at + 8]) < 1 || le32(&value[type_at + 12]) < 1)
      return "channel '" + channel + "' has a sampling rate below 1";
    if (pixel_bytes) *pixel_bytes += type == 1 ? 2 : 4;
    i = type_at + 16;
  }
  return i + 1 == value.size() ? "" : "the channel list does not end where its size says";
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
      // OpenEXR reads a value of a known type by its structure, not by the declared size: a size that disagrees
      // would have it read the following attributes from other offsets than this walk (a 51-byte channel list
      // whose last entry ran on had OpenEXR find a 13.6 M-pixel data window that this walk never saw).
      if (const int64_t fixed = fixed_value_size(type); fixed >= 0 && fixed != value_size)
        return {corrupt + "attribute '" + printable(name) + "' (" + printable(type) + ") has " +
                std::to_string(value_size) + " bytes, its type has " + std::to_string(fixed)};
      // The attributes that size the decoding buffers, and the variable-size types read by structure, are read;
      // the others skipped.
      const bool wanted = (name == "dataWindow" && type == "box2i") || (name == "compression" && type == "compression") ||
                          (name == "tiles" && type == "tiledesc") || type == "chlist" || type == "preview";
      if (!wanted) {
        in.seekg(value_size, std::ios::cur);
        continue;
      }
      value.resize(size_t(value_size));
      if (!in.read(reinterpret_cast<char*>(value.data()), value_size)) return {corrupt + "the file ends in '" + name + "'"};
      if (type == "preview") {  // width, height, then 4 bytes a pixel: OpenEXR allocates from the two counts
        const uint64_t pixels =
            value_size < 8 ? 0 : uint64_t(uint32_t(le32(&value[0]))) * uint32_t(le32(&value[4]));
        if (value_size < 8 || pixels > uint64_t(value_size) / 4 || pixels * 4 != uint64_t(value_size) - 8)
          return {corrupt + "the preview image '" + printable(name) + "' does not have the size its width and height say"};
      } else if (type == "chlist") {
        if (const std::string problem = channel_list_problem(value, name == "channels" ? &part.pixel_bytes : nullptr);
            !problem.empty())
          return {corrupt + "attribute '" + printable(name) + "': " + problem};
      } else if (name == "dataWindow") {
        part.width = int64_t(le32(&value[8])) - int64_t(le32(&value[0])) + 1;
      } else if (name == "compression") {
        part.compression = value[0];
      } else if (name == "tiles") {
        part.tile_width = uint32_t(le32(&value[0]));
        part.tile_height = uint32_t(le32(&value[4]));
      }
    }
    // A block or tile must be decodable from the bytes the file has: its decoded size is bounded by the file's
    // size times the compression's largest expansion. Beyond a floor that any sane block fits, a header claiming
    // more is refused before OpenEXR allocates it (a 445-byte file claiming a 13.7 M-pixel row of ZIP blocks made
    // it allocate 2.6 GB three times).
    constexpr uint64_t kAnyBlockFits = uint64_t(64) << 20;
    const uint64_t decode = part.decode_bytes();
    if (decode > kAnyBlockFits && decode / max_expansion(part.compression) > uint64_t(size))
      return {corrupt + "a block of " + std::to_string(part.tile_width > 0 ? part.tile_width : part.width) +
              " pixels wide needs " + std::to_string(decode) + " bytes of decoding buffers, more than a " +
              std::to_string(size) + "-byte file can decode to"};
    out.decode_bytes = std::max(out.decode_bytes, decode);
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
