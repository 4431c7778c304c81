#include "geometry/obj.h"

#include <charconv>
#include <cmath>
#include <set>
#include <cstring>
#include <filesystem>
#include <unordered_map>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/text.h"
#include "core/read_guard.h"
#include "geometry/mesh_io.h"

namespace torte {

namespace {

constexpr uint32_t kNone = UINT32_MAX;

// Statements that carry nothing a triangle mesh needs (lines, points, smoothing groups, free-form geometry,
// display attributes). Anything else unknown is an error, so a corrupt or non-OBJ file is not read as empty.
const char* const kIgnored[] = {"l",    "p",    "s",     "vp",   "cstype",   "deg",      "bmat",   "step",
                                "curv", "curv2", "surf", "parm", "trim",     "hole",     "scrv",   "sp",
                                "end",  "con",  "mg",    "lod",  "bevel",    "c_interp", "d_interp", "usemap",
                                "maplib", "shadow_obj", "trace_obj", "ctech", "stech", "call", "csh"};

// MTL statements torte reads nothing from (Ka, illum, maps other than map_Kd and bump, PBR extensions): skipped
// without a warning (docs/formats.md says which are honoured).
bool known_mtl_statement(std::string_view key) {
  static const char* const kKnown[] = {"Tf", "illum", "sharpness", "map_Ka", "map_Ks", "map_Ns", "map_d",
                                       "map_Ke", "disp", "decal", "refl", "Pr", "Pm", "Ps", "Pc", "Pcr",
                                       "aniso", "anisor", "map_Pr", "map_Pm", "map_Ps", "norm", "map_Kn"};
  for (const char* k : kKnown)
    if (key == k) return true;
  return false;
}

// Whitespace-separated tokens of one line.
struct Tokens {
  std::string_view rest;
  std::string_view next() {
    size_t i = 0;
    while (i < rest.size() && (rest[i] == ' ' || rest[i] == '\t')) ++i;
    size_t j = i;
    while (j < rest.size() && rest[j] != ' ' && rest[j] != '\t') ++j;
    const std::string_view t = rest.substr(i, j - i);
    rest.remove_prefix(j);
    return t;
  }
  // The rest of the line without surrounding blanks (names may contain spaces).
  std::string_view remainder() const {
    std::string_view r = rest;
    while (!r.empty() && (r.front() == ' ' || r.front() == '\t')) r.remove_prefix(1);
    while (!r.empty() && (r.back() == ' ' || r.back() == '\t')) r.remove_suffix(1);
    return r;
  }
};

bool parse_float(std::string_view t, float* out) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  const auto r = std::from_chars(t.data(), t.data() + t.size(), *out);
  return !t.empty() && r.ec == std::errc() && r.ptr == t.data() + t.size();
}

// Calls fn(line_number, line) for each line, with '\r' and leading blanks removed.
template <class Fn>
void for_each_line(std::string_view text, Fn fn) {
  size_t pos = 0, line_no = 0;
  while (pos < text.size()) {
    const char* nl = static_cast<const char*>(std::memchr(text.data() + pos, '\n', text.size() - pos));
    const size_t eol = nl ? size_t(nl - text.data()) : text.size();
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
    fn(line_no, line);
  }
}

std::string resolve(const std::string& base_dir, std::string_view file) {
  const std::filesystem::path p{std::string(file)};
  return p.is_absolute() || base_dir.empty() ? p.string() : (std::filesystem::path(base_dir) / p).string();
}

struct CornerKey {
  uint32_t v, t, n;
  bool operator==(const CornerKey&) const = default;
};
struct CornerHash {
  size_t operator()(const CornerKey& k) const {
    uint64_t h = (uint64_t(k.v) * 0x9E3779B97F4A7C15ull) ^ (uint64_t(k.t) << 21) ^ (uint64_t(k.n) * 0xC2B2AE3D27D4EB4Full);
    return size_t(h ^ (h >> 29));
  }
};

class Parser {
 public:
  Parser(const std::string& name, const std::string& base_dir) : name_(name), base_dir_(base_dir) {}

  ObjData run(std::string_view text) {
    out_.groups.push_back("");
    group_index_[""] = 0;
    for_each_line(text, [&](size_t n, std::string_view line) {
      line_ = n;
      statement(line);
    });
    finish();
    return std::move(out_);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw Error(escape_text(name_) + ": line " + std::to_string(line_) + ": " + problem);
  }

  void statement(std::string_view line) {
    if (line.empty() || line[0] == '#') return;
    Tokens tok{line};
    const std::string_view key = tok.next();
    if (key == "v") {
      float p[3];
      numbers(tok, p, 3, 3, "a vertex position needs 3 numbers");
      px_.push_back(p[0]), py_.push_back(p[1]), pz_.push_back(p[2]);
      first_.push_back(kNone);
    } else if (key == "vt") {
      float t[2] = {0, 0};
      numbers(tok, t, 1, 2, "a texture coordinate needs 1 to 3 numbers");
      tu_.push_back(t[0]), tv_.push_back(t[1]);
    } else if (key == "vn") {
      float n[3];
      numbers(tok, n, 3, 3, "a normal needs 3 numbers");
      vn_.emplace_back(n[0], n[1], n[2]);
    } else if (key == "f") {
      face(tok);
    } else if (key == "o" || key == "g") {
      const std::string name(tok.remainder());
      const auto [it, inserted] = group_index_.try_emplace(name, uint32_t(out_.groups.size()));
      if (inserted) out_.groups.push_back(name);
      group_ = it->second;
    } else if (key == "usemtl") {
      const std::string name(tok.remainder());
      auto it = material_index_.find(name);
      if (it == material_index_.end()) {
        out_.warnings.push_back(name_ + ": line " + std::to_string(line_) + ": material " + quote_text(name, 60) +
                                " is not defined in any mtllib file");
        it = material_index_.emplace(name, int32_t(out_.materials.size())).first;
        {
          ObjMaterial mat;
          mat.name = name;
          out_.materials.push_back(std::move(mat));
        }
      }
      material_ = it->second;
    } else if (key == "mtllib") {
      for (std::string_view f = tok.next(); !f.empty(); f = tok.next()) load_mtl(resolve(base_dir_, f));
    } else {
      for (const char* ignored : kIgnored)
        if (key == ignored) return;
      fail("unknown statement " + quote_text(key));
    }
  }

  // Reads between min_count and max_count numbers into out; more are allowed and ignored (w, vertex colours).
  void numbers(Tokens& tok, float* out, int min_count, int max_count, const char* what) {
    int n = 0;
    for (std::string_view t = tok.next(); !t.empty() && t[0] != '#'; t = tok.next(), ++n) {
      float f;
      if (!parse_float(t, &f)) fail(quote_text(t) + " is not a number");
      if (n < max_count) out[n] = f;
    }
    if (n < min_count) fail(what);
  }

  // One index of a face corner: 1-based, or negative counting back from the newest element.
  uint32_t index(std::string_view t, size_t count, const char* kind) {
    int64_t i = 0;
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    const auto r = std::from_chars(t.data(), t.data() + t.size(), i);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail("bad " + std::string(kind) + " index " + quote_text(t));
    if (i == 0) fail(std::string(kind) + " index 0 is invalid (OBJ indices start at 1)");
    const int64_t zero_based = i > 0 ? i - 1 : int64_t(count) + i;
    if (zero_based < 0 || zero_based >= int64_t(count))
      fail(std::string(kind) + " index " + std::to_string(i) + " is out of range (" + std::to_string(count) +
           " defined so far)");
    return uint32_t(zero_based);
  }

  void face(Tokens& tok) {
    corners_.clear();
    for (std::string_view c = tok.next(); !c.empty() && c[0] != '#'; c = tok.next()) {
      const size_t s1 = c.find('/');
      const size_t s2 = s1 == std::string_view::npos ? s1 : c.find('/', s1 + 1);
      const uint32_t v = index(c.substr(0, s1), px_.size(), "vertex");
      uint32_t t = kNone, n = kNone;
      if (s1 != std::string_view::npos) {
        const std::string_view ts = c.substr(s1 + 1, s2 == std::string_view::npos ? std::string_view::npos : s2 - s1 - 1);
        if (!ts.empty()) t = index(ts, tu_.size(), "texture coordinate");
        if (s2 != std::string_view::npos) n = index(c.substr(s2 + 1), vn_.size(), "normal");
        else if (ts.empty()) fail("bad face vertex " + quote_text(c));
      }
      corners_.push_back(vertex(v, t, n));
    }
    if (corners_.size() < 3) fail("a face needs at least 3 vertices");
    // A line of a few bytes can make many triangles (f 1 1 1 1 ...): every 2^20 of them the next batch is
    // checked against the memory budget.
    const size_t before = out_.mesh.triangle_count();
    if ((before + corners_.size()) >> 20 != before >> 20)
      reserve_memory((uint64_t(1) << 20) * 40, escape_text(name_) + ": line " + std::to_string(line_) +
                                                  ": the mesh (" + std::to_string(before) + " triangles so far)");
    // A fan around the first corner, as cornell-box.lua splits its quads.
    for (size_t k = 1; k + 1 < corners_.size(); ++k) {
      out_.mesh.add_triangle(corners_[0], corners_[k], corners_[k + 1]);
      out_.triangle_material.push_back(material_);
      out_.triangle_group.push_back(group_);
    }
  }

  // The output vertex for a (position, uv, normal) triple. Most positions appear with one triple only, so
  // the first is kept per position and only the others go to a hash map.
  uint32_t vertex(uint32_t v, uint32_t t, uint32_t n) {
    uint32_t& first = first_[v];
    if (first != kNone && out_t_[first] == t && out_n_[first] == n) return first;
    if (first == kNone) return first = add_vertex(v, t, n);
    const auto [it, inserted] = more_.try_emplace(CornerKey{v, t, n}, 0);
    if (inserted) it->second = add_vertex(v, t, n);
    return it->second;
  }

  uint32_t add_vertex(uint32_t v, uint32_t t, uint32_t n) {
    if (out_t_.size() >= kNone) fail("too many vertices");
    out_.mesh.add_vertex({px_[v], py_[v], pz_[v]});
    out_t_.push_back(t);
    out_n_.push_back(n);
    return uint32_t(out_t_.size() - 1);
  }

  void finish() {
    TriangleMesh& m = out_.mesh;
    size_t with_uv = 0, with_n = 0;
    for (size_t i = 0; i < out_t_.size(); ++i) with_uv += out_t_[i] != kNone, with_n += out_n_[i] != kNone;
    if (with_uv > 0) {  // corners without a uv get (0, 0)
      m.u.resize(out_t_.size()), m.v.resize(out_t_.size());
      for (size_t i = 0; i < out_t_.size(); ++i)
        if (out_t_[i] != kNone) m.u[i] = tu_[out_t_[i]], m.v[i] = tv_[out_t_[i]];
    }
    if (with_n > 0 && with_n < out_n_.size()) {
      out_.warnings.push_back(name_ + ": only some face corners have normals; all normals are ignored");
    } else if (with_n > 0) {
      for (size_t i = 0; i < out_n_.size(); ++i) {
        const Vec3f n = vn_[out_n_[i]];
        const float len = length(n);
        const Vec3f u = len > 0 && std::isfinite(len) ? n / len : Vec3f();  // zero: geometric normal is used
        m.nx.push_back(u.x), m.ny.push_back(u.y), m.nz.push_back(u.z);
      }
    }
    m.validate(name_);
  }

  void load_mtl(const std::string& path) {
    std::string text;
    try {
      check_nested_read(path);  // under --sandbox the file policy applies to what an OBJ names too
      text = read_file_bytes(path);
    } catch (const Error& e) {
      out_.warnings.push_back(name_ + ": line " + std::to_string(line_) + ": material library " + e.what());
      return;
    }
    const std::string dir = std::filesystem::path(path).parent_path().string();
    std::set<std::string> warned;
    int32_t current = -1;  // an index: materials may reallocate while the file adds more
    for_each_line(text, [&](size_t n, std::string_view line) {
      auto bad = [&](const std::string& problem) {
        throw Error(escape_text(path) + ": line " + std::to_string(n) + ": " + problem);
      };
      if (line.empty() || line[0] == '#') return;
      Tokens tok{line};
      const std::string_view key = tok.next();
      if (key == "newmtl") {
        const std::string name(tok.remainder());
        if (name.empty()) bad("newmtl needs a name");
        auto [it, inserted] = material_index_.try_emplace(name, int32_t(out_.materials.size()));
        if (inserted) {
          ObjMaterial mat;
          mat.name = name;
          out_.materials.push_back(std::move(mat));
        }
        current = it->second;
        out_.materials[current].defined = true;
      } else if (key == "Kd" || key == "Ke" || key == "Ka" || key == "Ks" || key == "Ns" || key == "Ni" || key == "d" ||
                 key == "Tr" || key == "map_Kd" || key == "map_Bump" || key == "bump" || key == "map_bump") {
        if (current < 0) bad(std::string(key) + " before any newmtl");
        ObjMaterial& mat = out_.materials[current];
        if (key.starts_with("map_") || key == "bump") {  // options (-s u v w, -bm 0.5, ...) first; the file last
          std::string_view last, t, prev;
          while (!(t = tok.next()).empty()) {
            if (prev == "-bm" && !parse_float(t, &mat.bump_scale)) bad("-bm needs a number, got " + quote_text(t));
            prev = t;
            last = t;
          }
          if (last.empty() || last[0] == '-') bad(std::string(key) + " needs a file name");
          (key == "map_Kd" ? mat.map_kd : mat.map_bump) = resolve(dir, last);
          return;
        }
        float c[3];
        int count = 0;
        for (std::string_view t = tok.next(); !t.empty() && t[0] != '#' && count < 3; t = tok.next(), ++count)
          if (!parse_float(t, &c[count])) bad(quote_text(t) + " is not a number");
        const bool scalar = key == "Ns" || key == "Ni" || key == "d" || key == "Tr";
        if (scalar ? count < 1 : count != 1 && count != 3)
          bad(std::string(key) + (scalar ? " needs a number" : " needs 1 or 3 numbers"));
        for (int i = 0; i < count; ++i)
          if (!std::isfinite(c[i]) || c[i] < 0) bad(std::string(key) + " must be finite and non-negative");
        const Rgb rgb = count == 1 ? Rgb(c[0]) : Rgb(c[0], c[1], c[2]);
        if (key == "Kd") mat.kd = rgb;
        else if (key == "Ke") mat.ke = rgb;
        else if (key == "Ka") mat.ka = rgb;
        else if (key == "Ks") mat.ks = rgb;
        else if (key == "Ns") mat.ns = c[0];
        else if (key == "Ni") mat.ni = c[0];
        else if (c[0] > 1) bad(std::string(key) + " must be in [0, 1]");
        else mat.d = key == "d" ? c[0] : 1 - c[0];
      } else if (!known_mtl_statement(key) && warned.insert(std::string(key)).second) {
        // Statements of extensions torte does not know are skipped, said once per file (a typo shows up here).
        out_.warnings.push_back(path + ": line " + std::to_string(n) + ": unknown MTL statement " +
                                quote_text(key) + " ignored");
      }
    });
    // Some files (the classic cornell_box.mtl among them) give a light's radiance as Ka: an ambient reflectance
    // above 1 cannot be a reflectance, so without a Ke it is read as emission.
    for (ObjMaterial& m : out_.materials)
      if (m.ke.is_black() && m.ka.max_component() > 1) m.ke = m.ka;
  }

  std::string name_, base_dir_;
  size_t line_ = 0;
  std::vector<float> px_, py_, pz_, tu_, tv_;
  std::vector<Vec3f> vn_;
  std::vector<uint32_t> first_, out_t_, out_n_, corners_;
  std::unordered_map<CornerKey, uint32_t, CornerHash> more_;
  std::unordered_map<std::string, int32_t> material_index_;
  std::unordered_map<std::string, uint32_t> group_index_;
  int32_t material_ = -1;
  uint32_t group_ = 0;
  ObjData out_;
};

}  // namespace

ObjData parse_obj(std::string_view text, const std::string& name, const std::string& base_dir) {
  return Parser(name, base_dir).run(text);
}

std::vector<ObjPart> split_by_material(const ObjData& data) {
  const TriangleMesh& m = data.mesh;
  std::vector<ObjPart> parts;
  std::unordered_map<int32_t, size_t> part_of;
  std::vector<std::vector<uint32_t>> remap;  // per part: source vertex -> part vertex (kNone = not yet)
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const int32_t mat = t < data.triangle_material.size() ? data.triangle_material[t] : -1;
    const auto [it, inserted] = part_of.try_emplace(mat, parts.size());
    if (inserted) {
      parts.push_back({mat, {}});
      remap.emplace_back(m.vertex_count(), kNone);
    }
    ObjPart& part = parts[it->second];
    std::vector<uint32_t>& map = remap[it->second];
    uint32_t c[3];
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = m.indices[3 * t + k];
      if (map[v] == kNone) {
        map[v] = uint32_t(part.mesh.vertex_count());
        part.mesh.add_vertex(m.position(v));
        if (m.has_uvs()) part.mesh.u.push_back(m.u[v]), part.mesh.v.push_back(m.v[v]);
        if (m.has_normals())
          part.mesh.nx.push_back(m.nx[v]), part.mesh.ny.push_back(m.ny[v]), part.mesh.nz.push_back(m.nz[v]);
      }
      c[k] = map[v];
    }
    part.mesh.add_triangle(c[0], c[1], c[2]);
  }
  return parts;
}

ObjData read_obj(const std::string& path) {
  return parse_obj(read_file_bytes(path), path, std::filesystem::path(path).parent_path().string());
}

}  // namespace torte
