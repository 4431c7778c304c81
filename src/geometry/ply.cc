#include "geometry/ply.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "core/file_read.h"
#include "core/memory_budget.h"
#include "core/text.h"
#include "geometry/mesh_io.h"

namespace torte {

namespace {

enum class Type : uint8_t { I8, U8, I16, U16, I32, U32, F32, F64 };
constexpr size_t kTypeSize[] = {1, 1, 2, 2, 4, 4, 4, 8};
size_t size_of(Type t) { return kTypeSize[int(t)]; }
bool is_float(Type t) { return t == Type::F32 || t == Type::F64; }

bool parse_type(std::string_view s, Type* t) {
  static const struct { const char* name; Type type; } kNames[] = {
      {"char", Type::I8},   {"int8", Type::I8},     {"uchar", Type::U8},   {"uint8", Type::U8},
      {"short", Type::I16}, {"int16", Type::I16},   {"ushort", Type::U16}, {"uint16", Type::U16},
      {"int", Type::I32},   {"int32", Type::I32},   {"uint", Type::U32},   {"uint32", Type::U32},
      {"float", Type::F32}, {"float32", Type::F32}, {"double", Type::F64}, {"float64", Type::F64}};
  for (const auto& n : kNames)
    if (s == n.name) {
      *t = n.type;
      return true;
    }
  return false;
}

// Where a vertex property's value goes.
enum Slot { kX, kY, kZ, kNX, kNY, kNZ, kU, kV, kSlotCount };

struct Property {
  std::string name;
  Type type = Type::F32;  // of the value, or of the list entries
  bool list = false;
  Type count_type = Type::U8;
  int slot = -1;  // vertex: a Slot; face: 0 for the index list; -1: skipped
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
  // Fewest bytes one element can take, so a corrupt count cannot make us reserve gigabytes.
  size_t min_bytes(bool ascii) const {
    size_t n = 0;
    for (const Property& p : props) n += ascii ? 2 : size_of(p.list ? p.count_type : p.type);
    return std::max<size_t>(n, 1);
  }
};

enum class Format { Ascii, BinaryLE, BinaryBE };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  size_t body = 0;  // offset of the first body byte
};

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

Header parse_header(std::string_view data, const std::string& name) {
  Header h;
  bool has_format = false;
  size_t pos = 0, line_no = 0;
  auto fail = [&](const std::string& problem) -> void {
    throw Error(escape_text(name) + ": header line " + std::to_string(line_no) + ": " + problem);
  };
  for (;;) {
    if (pos >= data.size()) {
      if (line_no == 0) throw Error(escape_text(name) + ": the file is empty");
      throw Error(escape_text(name) + ": the header is truncated (no end_header line)");
    }
    const size_t eol = data.find('\n', pos);
    if (eol == std::string_view::npos) {  // an unterminated last line cannot hold a whole header
      if (pos == 0 && data.substr(0, 3) != "ply")
        throw Error(escape_text(name) + ": not a PLY file (the first line is not 'ply')");
      throw Error(escape_text(name) + ": the header is truncated (no end_header line)");
    }
    std::string_view line = data.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line_no == 1) {
      if (line != "ply") throw Error(escape_text(name) + ": not a PLY file (the first line is not 'ply')");
      continue;
    }
    const std::vector<std::string_view> t = split(line);
    if (t.empty()) continue;
    const std::string_view key = t[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "end_header") {
      if (!has_format) fail("end_header before any format line");
      h.body = eol + 1;
      return h;
    }
    if (key == "format") {
      if (t.size() != 3) fail("bad format line " + quote_text(line));
      if (t[1] == "ascii") h.format = Format::Ascii;
      else if (t[1] == "binary_little_endian") h.format = Format::BinaryLE;
      else if (t[1] == "binary_big_endian") h.format = Format::BinaryBE;
      else fail("unknown format " + quote_text(t[1]));
      if (t[2] != "1.0" && t[2] != "1") fail("unsupported PLY version " + quote_text(t[2]));
      has_format = true;
    } else if (key == "element") {
      Element e;
      if (t.size() != 3) fail("bad element line " + quote_text(line));
      e.name = t[1];
      const auto r = std::from_chars(t[2].data(), t[2].data() + t[2].size(), e.count);
      if (r.ec != std::errc() || r.ptr != t[2].data() + t[2].size())
        fail("element " + quote_text(e.name) + " has a bad count " + quote_text(t[2]));
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (h.elements.empty()) fail("property before any element");
      Element& e = h.elements.back();
      Property p;
      const bool list = t.size() >= 2 && t[1] == "list";
      if (t.size() != (list ? 5u : 3u)) fail("bad property line " + quote_text(line));
      p.list = list;
      p.name = t.back();
      const std::string_view type = list ? t[3] : t[1];
      if (!parse_type(type, &p.type))
        fail("unsupported type " + quote_text(type) + " of property " + quote_text(p.name) + " of element " +
             quote_text(e.name));
      if (list) {
        if (!parse_type(t[2], &p.count_type) || is_float(p.count_type))
          fail("unsupported list count type " + quote_text(t[2]) + " of property " + quote_text(p.name) +
               " (an integer type is needed)");
      }
      e.props.push_back(std::move(p));
    } else {
      fail("unknown keyword " + quote_text(key));
    }
  }
}

// Thrown by the sources; read_body turns them into an Error naming the element.
struct EndOfData {};
struct BadValue {
  std::string problem;
};

// Binary body; Swap when the file's byte order differs from the machine's.
template <bool Swap>
class BinarySource {
 public:
  BinarySource(const char* p, const char* end) : p_(p), end_(end) {}
  size_t remaining() const { return size_t(end_ - p_); }
  const char* at() const { return p_; }
  void begin_element() {}
  void end_element() {}
  double scalar(Type t) {
    if (remaining() < size_of(t)) throw EndOfData{};
    double v = 0;
    switch (t) {
      case Type::I8: v = load<int8_t, uint8_t>(); break;
      case Type::U8: v = load<uint8_t, uint8_t>(); break;
      case Type::I16: v = load<int16_t, uint16_t>(); break;
      case Type::U16: v = load<uint16_t, uint16_t>(); break;
      case Type::I32: v = load<int32_t, uint32_t>(); break;
      case Type::U32: v = load<uint32_t, uint32_t>(); break;
      case Type::F32: v = load<float, uint32_t>(); break;
      case Type::F64: v = load<double, uint64_t>(); break;
    }
    return v;
  }
  void skip(Type t, uint64_t n) {
    if (n > remaining() / size_of(t)) throw EndOfData{};
    p_ += n * size_of(t);
  }

 private:
  template <class T, class U>
  T load() {
    U u;
    std::memcpy(&u, p_, sizeof u);
    p_ += sizeof u;
    if constexpr (Swap && sizeof(U) == 2) u = __builtin_bswap16(u);
    if constexpr (Swap && sizeof(U) == 4) u = __builtin_bswap32(u);
    if constexpr (Swap && sizeof(U) == 8) u = __builtin_bswap64(u);
    return std::bit_cast<T>(u);
  }
  const char* p_;
  const char* end_;
};

// ASCII body: one element per line, values separated by spaces or tabs, numbers parsed with std::from_chars.
class AsciiSource {
 public:
  AsciiSource(const char* p, const char* end, size_t line) : p_(p), end_(end), line_(line) {}
  size_t remaining() const { return size_t(end_ - p_); }
  const char* at() const { return p_; }
  size_t line() const { return line_; }
  // Skips blank lines before an element.
  void begin_element() {
    while (p_ < end_ && is_space(*p_)) {
      if (*p_ == '\n') ++line_;
      ++p_;
    }
    if (p_ == end_) throw EndOfData{};
  }
  // The rest of the line must be empty: a longer line means the file disagrees with its header. Every line
  // must end with a line break: without one the last number may have been cut short by truncation.
  void end_element() {
    skip_blanks();
    if (p_ == end_) throw EndOfData{};
    if (*p_ != '\n') throw BadValue{"more values on the line than the header declares"};
  }
  double scalar(Type t) {
    const std::string_view tok = token();
    const char* first = tok.data() + (tok[0] == '+' ? 1 : 0);
    const char* last = tok.data() + tok.size();
    std::from_chars_result r;
    if (t == Type::F32) {
      float f;  // parsed as float directly, so the value is the correctly rounded float, as a binary file holds
      r = std::from_chars(first, last, f);
      if (r.ec == std::errc() && r.ptr == last) return f;
    } else if (t == Type::F64) {
      double d;
      r = std::from_chars(first, last, d);
      if (r.ec == std::errc() && r.ptr == last) return d;
    } else {
      int64_t i;
      r = std::from_chars(first, last, i);
      if (r.ec == std::errc() && r.ptr == last) {
        static const int64_t kMin[] = {-128, 0, -32768, 0, INT32_MIN, 0}, kMax[] = {127, 255, 32767, 65535,
                                                                                    INT32_MAX, UINT32_MAX};
        if (i < kMin[int(t)] || i > kMax[int(t)])
          throw BadValue{"value " + quote_text(tok) + " is out of range for its type"};
        return double(i);
      }
    }
    throw BadValue{quote_text(tok) + " is not a valid " + (is_float(t) ? "number" : "integer")};
  }
  void skip(Type, uint64_t n) {
    for (uint64_t i = 0; i < n; ++i) token();
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  void skip_blanks() {
    while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r')) ++p_;
  }
  std::string_view token() {
    skip_blanks();
    if (p_ == end_) throw EndOfData{};
    if (*p_ == '\n') throw BadValue{"fewer values on the line than the header declares"};
    const char* start = p_;
    while (p_ < end_ && !is_space(*p_)) ++p_;
    return {start, size_t(p_ - start)};
  }
  const char* p_;
  const char* end_;
  size_t line_;
};

size_t line_of(const AsciiSource& s) { return s.line(); }
template <bool Swap>
size_t line_of(const BinarySource<Swap>&) { return 0; }

template <class Src>
uint64_t list_count(Src& src, Type t) {
  const double n = src.scalar(t);
  if (n < 0) throw BadValue{"negative list length " + std::to_string(int64_t(n))};
  return uint64_t(n);
}

// Reads every element in file order into `m`; `vertex`/`face` point into h.elements (face may be null).
template <class Src>
void read_body(Src& src, const Header& h, const Element* vertex, const Element* face, TriangleMesh& m,
               const std::string& name, const PlyRelease& release) {
  // Every 2^16 elements the bytes behind go back (read_ply): the file and the mesh are not held whole together.
  const auto maybe_release = [&](uint64_t i) {
    if (release && (i & 0xFFFF) == 0) release(src.at());
  };
  const bool ascii = h.format == Format::Ascii;
  const uint64_t body_bytes = src.remaining();
  bool slot_used[kSlotCount] = {};
  for (const Property& p : vertex->props)
    if (p.slot >= 0) slot_used[p.slot] = true;
  std::vector<float>* dest[kSlotCount] = {&m.x, &m.y, &m.z, &m.nx, &m.ny, &m.nz, &m.u, &m.v};
  std::vector<uint32_t> poly;
  for (const Element& e : h.elements) {
    const uint64_t reservable = std::min<uint64_t>(e.count, src.remaining() / e.min_bytes(ascii) + 1);
    uint64_t i = 0;
    try {
      if (&e == vertex) {
        for (int s = 0; s < kSlotCount; ++s)
          if (slot_used[s]) dest[s]->reserve(reservable);
        for (; i < e.count; ++i) {
          maybe_release(i);
          src.begin_element();
          for (const Property& p : e.props) {
            if (p.list) {
              src.skip(p.type, list_count(src, p.count_type));
            } else {
              const double v = src.scalar(p.type);
              if (p.slot >= 0) dest[p.slot]->push_back(float(v));
            }
          }
          src.end_element();
        }
      } else if (&e == face) {
        m.indices.reserve(3 * reservable);
        for (; i < e.count; ++i) {
          maybe_release(i);
          src.begin_element();
          for (const Property& p : e.props) {
            const uint64_t n = p.list ? list_count(src, p.count_type) : 1;
            if (p.slot != 0) {
              if (p.list) src.skip(p.type, n);
              else src.scalar(p.type);
              continue;
            }
            poly.clear();
            for (uint64_t k = 0; k < n; ++k) {
              const double idx = src.scalar(p.type);
              if (idx < 0 || idx >= double(vertex->count))
                throw BadValue{"vertex index " + std::to_string(int64_t(idx)) + " is out of range (" +
                               std::to_string(vertex->count) + " vertices)"};
              poly.push_back(uint32_t(idx));
            }
            // Polygons become a fan around their first vertex; fewer than 3 vertices make no triangle. Past the
            // triangle per face reserved for, every 2^20 more are checked against the memory budget.
            const size_t before = m.triangle_count();
            if (poly.size() > 3 && before >= face->count && (before + poly.size()) >> 20 != before >> 20)
              reserve_memory((uint64_t(1) << 20) * 12,
                             escape_text(name) + ": " + std::to_string(before) + " triangles from polygons");
            for (size_t k = 1; k + 1 < poly.size(); ++k) m.add_triangle(poly[0], poly[k], poly[k + 1]);
          }
          src.end_element();
        }
      } else {
        for (; i < e.count; ++i) {
          src.begin_element();
          for (const Property& p : e.props) src.skip(p.type, p.list ? list_count(src, p.count_type) : 1);
          src.end_element();
        }
      }
    } catch (const EndOfData&) {
      // When the count alone cannot fit the file, say so: a corrupt count rather than a cut file.
      const uint64_t body = body_bytes, least = e.min_bytes(ascii);
      const std::string why = e.count > body / least + 1
                                  ? " (the header declares " + std::to_string(e.count) + ", which need at least " +
                                        std::to_string(least) + " bytes each; " + std::to_string(body) +
                                        " bytes follow the header)"
                                  : std::string();
      throw Error(escape_text(name) + ": " + escape_text(e.name, 40) + " " + std::to_string(i) + " of " +
                  std::to_string(e.count) + ": file ends early" + why);
    } catch (const BadValue& b) {
      const size_t line = line_of(src);
      throw Error(escape_text(name) + ": " + escape_text(e.name, 40) + " " + std::to_string(i) + " of " +
                  std::to_string(e.count) +
                  (line ? " (line " + std::to_string(line) + ")" : std::string()) + ": " + b.problem);
    }
  }
}

// Marks the properties the mesh needs; throws if x, y, z or the face index list is missing.
void assign_slots(Element& vertex, Element* face, const std::string& name) {
  auto find = [&](const char* n) -> Property* {
    for (Property& p : vertex.props)
      if (!p.list && p.name == n) return &p;
    return nullptr;
  };
  const char* xyz[] = {"x", "y", "z"};
  for (int s = 0; s < 3; ++s) {
    Property* p = find(xyz[s]);
    if (!p) throw Error(escape_text(name) + ": the vertex element has no scalar property '" + xyz[s] + "'");
    p->slot = s;
  }
  Property *nx = find("nx"), *ny = find("ny"), *nz = find("nz");
  if (nx && ny && nz) nx->slot = kNX, ny->slot = kNY, nz->slot = kNZ;
  const char* uv_names[][2] = {{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
  for (const auto& pair : uv_names) {
    Property *u = find(pair[0]), *v = find(pair[1]);
    if (u && v) {
      u->slot = kU, v->slot = kV;
      break;
    }
  }
  if (!face) return;
  for (Property& p : face->props)
    if (p.name == "vertex_indices" || p.name == "vertex_index") {
      if (!p.list) throw Error(escape_text(name) + ": the face property '" + p.name + "' must be a list");
      if (is_float(p.type)) throw Error(escape_text(name) + ": the face property '" + p.name + "' must hold integers");
      p.slot = 0;
      return;
    }
  throw Error(escape_text(name) + ": the face element has no 'vertex_indices' list");
}

}  // namespace

TriangleMesh parse_ply(std::string_view data, const std::string& name, const PlyRelease& release) {
  Header h = parse_header(data, name);
  Element *vertex = nullptr, *face = nullptr;
  for (Element& e : h.elements) {
    if (e.name == "vertex" && !vertex) vertex = &e;
    if (e.name == "face" && !face) face = &e;
  }
  if (!vertex) throw Error(escape_text(name) + ": the file has no vertex element");
  if (vertex->count > UINT32_MAX)
    throw Error(escape_text(name) + ": the header declares " + std::to_string(vertex->count) +
                " vertices, more than the limit of 4294967295 (2^32 - 1)");
  assign_slots(*vertex, face, name);
  {
    // What the counts ask for (a triangle per face; larger polygons are checked as they come), as far as the
    // file can hold them: vertex arrays of the properties used, and the index triples.
    const bool ascii = h.format == Format::Ascii;
    const uint64_t body = data.size() - h.body;
    const uint64_t nv = std::min<uint64_t>(vertex->count, body / vertex->min_bytes(ascii) + 1);
    const uint64_t nf = face ? std::min<uint64_t>(face->count, body / face->min_bytes(ascii) + 1) : 0;
    uint64_t per_vertex = 12;
    for (const Property& p : vertex->props) per_vertex += p.slot >= kNX ? 4 : 0;
    reserve_memory(nv * per_vertex + nf * 12, escape_text(name) + " (" + std::to_string(vertex->count) +
                                                  " vertices, " + std::to_string(face ? face->count : 0) + " faces)");
  }

  TriangleMesh m;
  const char* body = data.data() + h.body;
  const char* end = data.data() + data.size();
  if (h.format == Format::Ascii) {
    const size_t header_lines = size_t(std::count(data.data(), body, '\n'));
    AsciiSource src(body, end, header_lines + 1);
    read_body(src, h, vertex, face, m, name, release);
  } else if ((h.format == Format::BinaryBE) == (std::endian::native == std::endian::big)) {
    BinarySource<false> src(body, end);
    read_body(src, h, vertex, face, m, name, release);
  } else {
    BinarySource<true> src(body, end);
    read_body(src, h, vertex, face, m, name, release);
  }
  // Unit normals as the renderer expects; zero or broken ones become zero (geometric normal at shading).
  for (size_t i = 0; i < m.nx.size(); ++i) {
    const Vec3f n = m.normal(uint32_t(i));
    const float len = length(n);
    const Vec3f u = len > 0 && std::isfinite(len) ? n / len : Vec3f();
    m.nx[i] = u.x, m.ny[i] = u.y, m.nz[i] = u.z;
  }
  m.validate(name);
  return m;
}

TriangleMesh read_ply(const std::string& path) {
  FileBytes file(path);
  return parse_ply(file.bytes(), path, [&file](const char* p) { file.release_before(p); });
}

void write_ply(const TriangleMesh& mesh, const std::string& path) {
  static_assert(std::endian::native == std::endian::little, "write_ply writes the host's byte order");
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw Error(escape_text(path) + ": cannot be written (" + std::strerror(errno) + ")");
  const bool normals = mesh.has_normals(), uvs = mesh.has_uvs();
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by torte\nelement vertex " +
                       std::to_string(mesh.vertex_count()) + "\nproperty float x\nproperty float y\nproperty float z\n";
  if (normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
  if (uvs) header += "property float u\nproperty float v\n";
  header += "element face " + std::to_string(mesh.triangle_count()) +
            "\nproperty list uchar uint vertex_indices\nend_header\n";
  std::vector<char> block;
  bool ok = std::fwrite(header.data(), 1, header.size(), f) == header.size();
  const auto put = [&block](const void* p, size_t n) {
    const char* c = static_cast<const char*>(p);
    block.insert(block.end(), c, c + n);
  };
  const auto flush = [&] {
    ok = ok && std::fwrite(block.data(), 1, block.size(), f) == block.size();
    block.clear();
  };
  constexpr size_t kBlock = size_t(1) << 20;
  for (size_t i = 0; i < mesh.vertex_count() && ok; ++i) {
    const Vec3f p = mesh.position(uint32_t(i));
    put(&p, 12);
    if (normals) {
      const Vec3f n = mesh.normal(uint32_t(i));
      put(&n, 12);
    }
    if (uvs) {
      const Vec2f t = mesh.uv(uint32_t(i));
      put(&t, 8);
    }
    if (block.size() >= kBlock) flush();
  }
  for (size_t t = 0; t < mesh.triangle_count() && ok; ++t) {
    const uint8_t three = 3;
    put(&three, 1);
    put(mesh.triangle(t), 12);
    if (block.size() >= kBlock) flush();
  }
  flush();
  const int err = ok ? 0 : errno;
  if (std::fclose(f) != 0 && ok) ok = false;
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(err ? err : errno);
    std::remove(tmp.c_str());
    throw Error(escape_text(path) + ": cannot be written (" + why + ")");
  }
}

}  // namespace torte
