// Mesh files (PLY in all three encodings, OBJ + MTL, load_mesh) on the real models in ../shared/data/meshes and
// on small files written here, including truncated and corrupt ones (subdivision: test_subdivide.cc).
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/file_read.h"
#include "geometry/mesh_io.h"
#include "geometry/obj.h"
#include "geometry/ply.h"
#include "octahedron.h"

using namespace torte;
using test::kOcta, test::kOctaTris, test::octahedron;
namespace fs = std::filesystem;

namespace {

const std::string kMeshes = std::string(TORTE_SHARED_DATA) + "/meshes/";

bool have(const std::string& file) {
  if (fs::exists(kMeshes + file)) return true;
  WARN("skipped: " << kMeshes + file << " is absent (shared test data not installed)");
  return false;
}

// A fresh directory per test case and process, removed afterwards.
struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name)
      : path(fs::temp_directory_path() / ("torte_mesh_io_" + std::to_string(getpid()) + "_" + name)) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string p = (path / name).string();
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }
};

std::string slurp(const std::string& path) { return read_file_bytes(path); }

// The message of the torte::Error that fn throws ("" if it throws none).
template <class Fn>
std::string error_of(Fn fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Binary PLY values in either byte order.
template <class T>
void put(std::string& out, T value, bool big_endian) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof b);
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof b);
  out.append(b, sizeof b);
}

// The octahedron as PLY: positions as double in z y x order, a 'confidence' float, a vertex list property, an
// extra element before and after, and faces with a ushort count / uint indices plus a trailing uchar property.
std::string octa_ply(const std::string& format) {
  const bool ascii = format == "ascii", be = format == "binary_big_endian";
  std::string s = "ply\r\nformat " + format + " 1.0\ncomment written by test_mesh_io\nobj_info extra lines\n"
                  "element camera 1\nproperty float view_px\nproperty list uchar float tags\n"
                  "element vertex 6\nproperty double z\nproperty double y\nproperty float confidence\n"
                  "property list uchar short neighbours\nproperty double x\n"
                  "element face 8\nproperty list ushort uint vertex_indices\nproperty uchar flags\n"
                  "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  std::ostringstream a;
  if (ascii) a << "0.5 2 7 8\n";
  else put(s, 0.5f, be), put(s, uint8_t(2), be), put(s, 7.0f, be), put(s, 8.0f, be);
  for (const auto& p : kOcta) {
    if (ascii) a << p[2] << ' ' << p[1] << " 0.25 3 1 2 3 " << p[0] << '\n';
    else {
      put(s, p[2], be), put(s, p[1], be), put(s, 0.25f, be), put(s, uint8_t(3), be);
      for (int16_t k = 1; k <= 3; ++k) put(s, k, be);
      put(s, p[0], be);
    }
  }
  for (const auto& t : kOctaTris) {
    if (ascii) a << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << " 9\n";
    else {
      put(s, uint16_t(3), be);
      for (int k = 0; k < 3; ++k) put(s, uint32_t(t[k]), be);
      put(s, uint8_t(9), be);
    }
  }
  if (ascii) a << "0 1\n";
  else put(s, int32_t(0), be), put(s, int32_t(1), be);
  return s + a.str();
}

void check_same(const TriangleMesh& a, const TriangleMesh& b) {
  REQUIRE(a.vertex_count() == b.vertex_count());
  CHECK(a.x == b.x);  // bit-exact float comparison of whole arrays
  CHECK(a.y == b.y);
  CHECK(a.z == b.z);
  CHECK(a.indices == b.indices);
}

}  // namespace

TEST_CASE("PLY: ascii and binary bunny are identical", "[mesh_io]") {
  if (!have("bunny/bun_zipper.ply") || !have("bunny/bunny_binary_le.ply")) return;
  const TriangleMesh ascii = read_ply(kMeshes + "bunny/bun_zipper.ply");
  const TriangleMesh binary = read_ply(kMeshes + "bunny/bunny_binary_le.ply");
  CHECK(ascii.vertex_count() == 35947);
  CHECK(ascii.triangle_count() == 69451);
  CHECK_FALSE(ascii.has_normals());
  check_same(ascii, binary);
}

TEST_CASE("PLY: dragon counts, normals and bounds; Stanford ascii models", "[mesh_io]") {
  if (have("dragon/dragon_100k_binary_le.ply")) {
    const auto t0 = std::chrono::steady_clock::now();
    const TriangleMesh m = load_mesh(kMeshes + "dragon/dragon_100k_binary_le.ply");
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (s > 0.2) WARN("loading the dragon took " << s << " s (target < 0.2 s)");
    CHECK(m.vertex_count() == 50002);
    CHECK(m.triangle_count() == 100000);
    REQUIRE(m.has_normals());
    for (size_t i = 0; i < m.vertex_count(); i += 97) CHECK(length(m.normal(uint32_t(i))) == Approx(1).margin(1e-5));
    Bounds3f b;
    for (size_t i = 0; i < m.vertex_count(); ++i) b.extend(m.position(uint32_t(i)));
    CHECK(b.lo.x == Approx(-98.7).margin(0.1));
    CHECK(b.lo.y == Approx(-41.3).margin(0.1));
    CHECK(b.lo.z == Approx(-57.3).margin(0.1));
    CHECK(b.hi.x == Approx(103.1).margin(0.1));
    CHECK(b.hi.y == Approx(49.3).margin(0.1));
    CHECK(b.hi.z == Approx(76.9).margin(0.1));
  }
  if (have("happy-buddha/happy_vrip_res3.ply")) {
    const TriangleMesh m = read_ply(kMeshes + "happy-buddha/happy_vrip_res3.ply");
    CHECK(m.vertex_count() == 32328);
    CHECK(m.triangle_count() == 67240);
  }
  if (have("bunny/bun_zipper_res4.ply")) {
    const TriangleMesh m = load_mesh(kMeshes + "bunny/bun_zipper_res4.ply");
    CHECK(m.vertex_count() == 453);
    CHECK(m.triangle_count() == 948);
  }
}

TEST_CASE("PLY: ascii, little and big endian agree; doubles, property order, extra data", "[mesh_io]") {
  const TriangleMesh want = octahedron();
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    INFO(format);
    const TriangleMesh m = parse_ply(octa_ply(format), "octa.ply");
    check_same(m, want);
    CHECK_FALSE(m.has_normals());
    CHECK_FALSE(m.has_uvs());
  }
  TempDir dir("endian");
  const std::string path = dir.write("octa_be.PLY", octa_ply("binary_big_endian"));
  check_same(load_mesh(path), want);  // the extension is matched case-insensitively
}

TEST_CASE("PLY: polygons, normals, uv names, integer positions", "[mesh_io]") {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 5\n";
  SECTION("quads and pentagons are fans; short x y z and s t") {
    const TriangleMesh m = parse_ply(head + "property short x\nproperty short y\nproperty short z\n"
                                            "property float s\nproperty float t\n"
                                            "element face 2\nproperty list uchar int vertex_index\nend_header\n"
                                            "0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n-1 0 0 0.5 0.5\n"
                                            "4 0 1 2 3\n5 0 1 2 3 4\n",
                                     "poly.ply");
    CHECK(m.indices == std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3, 0, 3, 4});
    CHECK(m.x[4] == -1);
    REQUIRE(m.has_uvs());
    CHECK(m.u[4] == 0.5f);
    CHECK(m.v[2] == 1);
  }
  SECTION("normals are normalized; texture_u / texture_v") {
    const TriangleMesh m = parse_ply(head + "property float x\nproperty float y\nproperty float z\n"
                                            "property float nx\nproperty float ny\nproperty float nz\n"
                                            "property float texture_u\nproperty float texture_v\n"
                                            "element face 1\nproperty list uchar uint vertex_indices\nend_header\n"
                                            "0 0 0 0 0 2 0 0\n1 0 0 0 0 3 1 0\n0 1 0 0 0 0 0 1\n"
                                            "1 1 0 3 4 0 1 1\n2 2 0 0 0 1 1 1\n3 0 1 2\n",
                                     "normals.ply");
    REQUIRE(m.has_normals());
    CHECK(m.nz[0] == 1);
    CHECK(m.nx[2] == 0);  // a zero normal stays zero
    CHECK(m.nx[3] == Approx(0.6f));
    CHECK(m.ny[3] == Approx(0.8f));
    CHECK(m.u[1] == 1);
    CHECK(m.triangle_count() == 1);
  }
}

TEST_CASE("PLY: corrupt headers and bodies give one error naming the file", "[mesh_io]") {
  const std::string ok_head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n";
  const std::string ok_body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  REQUIRE(parse_ply(ok_head + "end_header\n" + ok_body, "ok.ply").triangle_count() == 1);
  auto err = [](const std::string& text) { return error_of([&] { parse_ply(text, "bad.ply"); }); };
  using Catch::Contains;
  using Catch::StartsWith;
  CHECK_THAT(err(""), StartsWith("bad.ply: ") && Contains("empty"));
  CHECK_THAT(err("solid cube\n"), StartsWith("bad.ply: ") && Contains("not a PLY file"));
  CHECK_THAT(err(ok_head), Contains("header is truncated"));
  CHECK_THAT(err("ply\nformat binary_middle_endian 1.0\nend_header\n"), Contains("binary_middle_endian"));
  CHECK_THAT(err("ply\nformat ascii\nend_header\n"), Contains("header line 2") && Contains("bad format line"));
  CHECK_THAT(err("ply\nformat ascii 1.0\nelement vertex 1\nproperty int128 x\nend_header\n"),
             Contains("unsupported type 'int128'") && Contains("'x'"));
  CHECK_THAT(err("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                 "element face 1\nproperty list float int vertex_indices\nend_header\n"),
             Contains("list count type 'float'"));
  CHECK_THAT(err("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nend_header\n"), Contains("'y'"));
  CHECK_THAT(err("ply\nformat ascii 1.0\nelement vertex -3\nend_header\n"), Contains("bad count '-3'"));
  CHECK_THAT(err("ply\nformat ascii 1.0\nbogus line\nend_header\n"), Contains("unknown keyword 'bogus'"));
  CHECK_THAT(err(ok_head + "end_header\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n"),
             Contains("vertex 1 of 3 (line 11)") && Contains("fewer values"));
  CHECK_THAT(err(ok_head + "end_header\n0 0 0\n1 0 0 7\n0 1 0\n3 0 1 2\n"), Contains("more values"));
  CHECK_THAT(err(ok_head + "end_header\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n"), Contains("'zero' is not a valid number"));
  CHECK_THAT(err(ok_head + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
             Contains("face 0 of 1") && Contains("vertex index 3 is out of range (3 vertices)"));
  CHECK_THAT(err(ok_head + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"), Contains("vertex index -1"));
  CHECK_THAT(err(ok_head + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n"), Contains("'2.5' is not a valid integer"));
  CHECK_THAT(err(ok_head + "end_header\n0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n"), Contains("out of range for its type"));
  CHECK_THAT(err(ok_head + "end_header\n0 0 0\n1 0 0\n"), Contains("vertex 2 of 3: file ends early"));
  CHECK_THAT(err(ok_head + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1"), Contains("face 0 of 1: file ends early"));
  CHECK_THAT(err(ok_head + "end_header\n0 0 0\n1 0 0\n0 1 nan\n3 0 1 2\n"), Contains("non-finite"));
}

TEST_CASE("PLY: truncated and corrupted copies of the real files", "[mesh_io]") {
  if (!have("dragon/dragon_100k_binary_le.ply") || !have("bunny/bun_zipper_res4.ply")) return;
  TempDir dir("truncated");
  const std::string dragon = slurp(kMeshes + "dragon/dragon_100k_binary_le.ply");
  const size_t body = dragon.find("end_header\n") + 11;
  REQUIRE(dragon.size() == body + 50002 * 24 + 100000 * 13);
  struct Cut { size_t size; std::string message; };
  const Cut cuts[] = {{40, "header is truncated"},
                      {body, "vertex 0 of 50002: file ends early"},
                      {body + 1234 * 24 + 10, "vertex 1234 of 50002: file ends early"},
                      {body + 50002 * 24 + 13 * 777 + 5, "face 777 of 100000: file ends early"},
                      {dragon.size() - 1, "face 99999 of 100000: file ends early"}};
  for (const Cut& c : cuts) {
    const std::string path = dir.write("dragon_cut.ply", dragon.substr(0, c.size));
    const std::string e = error_of([&] { read_ply(path); });
    CHECK_THAT(e, Catch::StartsWith(path + ": ") && Catch::Contains(c.message));
  }
  std::string bad_index = dragon;
  const int32_t huge = 999999;
  std::memcpy(&bad_index[body + 50002 * 24 + 13 * 5 + 1 + 4], &huge, 4);  // face 5, second index
  const std::string path = dir.write("dragon_bad.ply", bad_index);
  CHECK_THAT(error_of([&] { read_ply(path); }),
             Catch::Contains("face 5 of 100000") && Catch::Contains("vertex index 999999 is out of range"));

  const std::string bunny = slurp(kMeshes + "bunny/bun_zipper_res4.ply");
  for (size_t size : {bunny.size() / 3, bunny.size() / 2, bunny.size() - 3}) {
    const std::string p = dir.write("bunny_cut.ply", bunny.substr(0, size));
    CHECK_THAT(error_of([&] { read_ply(p); }), Catch::StartsWith(p + ": ") && Catch::Contains("file ends early"));
  }
}

TEST_CASE("OBJ: the real files", "[mesh_io]") {
  if (have("spot/spot_triangulated.obj")) {
    const std::string path = kMeshes + "spot/spot_triangulated.obj";
    const ObjData d = read_obj(path);
    CHECK(d.mesh.triangle_count() == 5856);
    CHECK(d.mesh.has_uvs());
    CHECK_FALSE(d.mesh.has_normals());
    // Independently: one vertex per distinct (position, uv) pair used by the faces.
    std::set<std::string> corners;
    std::istringstream in(slurp(path));
    for (std::string line; std::getline(in, line);)
      if (line.rfind("f ", 0) == 0) {
        std::istringstream f(line.substr(2));
        for (std::string c; f >> c;) corners.insert(c);
      }
    CHECK(d.mesh.vertex_count() == corners.size());
    std::set<std::pair<float, float>> uvs;  // every vertex's uv is one of the file's vt lines
    std::istringstream vts(slurp(path));
    for (std::string line; std::getline(vts, line);)
      if (line.rfind("vt ", 0) == 0) {
        std::istringstream f(line.substr(3));
        float u, v;
        f >> u >> v;
        uvs.insert({u, v});
      }
    size_t matched = 0;
    for (size_t i = 0; i < d.mesh.vertex_count(); ++i) matched += uvs.count({d.mesh.u[i], d.mesh.v[i]});
    CHECK(matched == d.mesh.vertex_count());
  }
  if (have("lucy/lucy_100k.obj")) {
    const TriangleMesh m = load_mesh(kMeshes + "lucy/lucy_100k.obj");
    CHECK(m.vertex_count() == 49987);
    CHECK(m.triangle_count() == 99970);
  }
  if (have("cornell-box/cornell_box.obj")) {
    const ObjData d = read_obj(kMeshes + "cornell-box/cornell_box.obj");
    CHECK(d.mesh.triangle_count() == 36);
    CHECK(d.warnings.empty());
    REQUIRE(d.materials.size() == 5);
    CHECK(d.materials[1].name == "red");
    CHECK(d.materials[1].kd == Rgb(1, 0, 0));
    CHECK(d.materials[4].name == "light");
    REQUIRE(d.triangle_material.size() == 36);
    CHECK(d.materials[d.triangle_material[0]].name == "white");                          // floor
    CHECK(d.materials[d.triangle_material[6]].name == "light");                          // after 3 floor quads
    CHECK(d.groups[d.triangle_group[6]] == "light");
    CHECK(d.groups[d.triangle_group[35]] == "tall_block");
    // The light quad "f -4 -3 -2 -1" refers to vertices 13..16 and becomes the fan (13, 14, 15), (13, 15, 16).
    CHECK(d.mesh.position(d.mesh.indices[18]) == Vec3f(343, 548, 227));
    CHECK(d.mesh.position(d.mesh.indices[20]) == Vec3f(213, 548, 332));
    CHECK(d.mesh.position(d.mesh.indices[23]) == Vec3f(213, 548, 227));
  }
}

TEST_CASE("OBJ: v/vt/vn combinations, splitting, negative indices, materials", "[mesh_io]") {
  TempDir dir("obj");
  dir.write("m.mtl", "# materials\nnewmtl skin\nKa 1 1 1\nKd 0.5 0.25 0.125\nmap_Kd -s 1 1 1 tex/skin.png\n"
                     "newmtl lamp\nKe 4\n");
  const std::string path = dir.write("t.obj",
      "mtllib m.mtl\n\n  # indented comment\nv 0 0 0\nv 1 0 0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5 0\nvn 0 0 2\n"
      "g left\nusemtl skin\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"
      "o right\nusemtl lamp\nf -4/-1/-1 -2/-2/-1 -1/-1/-1\n"
      "usemtl unknown\nf 1/5/1 2/2/1 3/3/1\r\n");
  const ObjData d = read_obj(path);
  const TriangleMesh& m = d.mesh;
  REQUIRE(m.triangle_count() == 4);
  CHECK(m.indices[0] == 0);
  CHECK(m.indices[3] == 0);  // fan: (0,1,2), (0,2,3)
  // Positions 1, 3 and 4 are used with two uvs each (1 and 5, 3 and 4, 4 and 5): 4 + 3 distinct corners.
  CHECK(m.vertex_count() == 7);
  REQUIRE(m.has_uvs());
  REQUIRE(m.has_normals());
  CHECK(m.nz[0] == 1);
  const uint32_t a = m.indices[6];  // "-4/-1" = position 1 (index 0) with uv 5
  CHECK(m.position(a) == Vec3f(0, 0, 0));
  CHECK(m.u[a] == 0.5f);
  CHECK(m.position(m.indices[8]) == Vec3f(0, 1, 0));
  REQUIRE(d.materials.size() == 3);
  CHECK(d.materials[0].kd == Rgb(0.5f, 0.25f, 0.125f));
  CHECK(d.materials[0].map_kd == (dir.path / "tex/skin.png").string());
  CHECK(d.materials[1].ke == Rgb(4));
  CHECK(d.materials[2].name == "unknown");
  CHECK(d.triangle_material == std::vector<int32_t>{0, 0, 1, 2});
  CHECK(d.groups[d.triangle_group[0]] == "left");
  CHECK(d.groups[d.triangle_group[3]] == "right");
  CHECK(d.warnings.size() == 1);  // the unknown material
}

TEST_CASE("OBJ and load_mesh errors name the file and line", "[mesh_io]") {
  auto err = [](const std::string& text) { return error_of([&] { parse_obj(text, "bad.obj", ""); }); };
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  using Catch::Contains;
  CHECK_THAT(err(tri + "f 1 2 4\n"), Contains("bad.obj: line 4: vertex index 4 is out of range (3 defined"));
  CHECK_THAT(err(tri + "f 1 2 -4\n"), Contains("vertex index -4 is out of range"));
  CHECK_THAT(err(tri + "f 0 1 2\n"), Contains("index 0 is invalid"));
  CHECK_THAT(err(tri + "f 1/1 2/1 3/1\n"), Contains("texture coordinate index 1 is out of range"));
  CHECK_THAT(err(tri + "f 1//2 2//2 3//2\n"), Contains("normal index 2 is out of range"));
  CHECK_THAT(err(tri + "f 1 2\n"), Contains("at least 3 vertices"));
  CHECK_THAT(err(tri + "f 1 x 3\n"), Contains("bad vertex index 'x'"));
  CHECK_THAT(err("v 0 0 zero\n"), Contains("line 1: 'zero' is not a number"));
  CHECK_THAT(err("v 0 0\n"), Contains("needs 3 numbers"));
  CHECK_THAT(err("\x89PNG\n"), Contains("unknown statement"));
  CHECK(err(tri + "mtllib missing.mtl\nf 1 2 3\n").empty());  // a missing library is a warning only

  TempDir dir("errors");
  const std::string missing = (dir.path / "nothing.ply").string();
  CHECK_THAT(error_of([&] { load_mesh(missing); }), Contains(missing) && Contains("cannot open"));
  const std::string stl = dir.write("mesh.stl", "solid x\n");
  CHECK_THAT(error_of([&] { load_mesh(stl); }), Contains(stl) && Contains("unknown mesh file type '.stl'"));
  CHECK_THAT(error_of([&] { load_mesh(dir.path.string()); }), Contains("no extension"));
  CHECK(load_mesh(dir.write("UP.OBJ", tri + "f 1 2 3\n")).triangle_count() == 1);
}

TEST_CASE("PLY: write_ply round-trips positions, normals, uvs and triples exactly", "[mesh_io][ply_write]") {
  TempDir dir("ply_write");
  TriangleMesh m;
  const float coords[5][3] = {{0, 0, 0}, {1.5f, -2.25f, 3e-7f}, {-1e6f, 0.1f, 7}, {0.3f, 0.7f, -0.9f}, {2, 2, 2}};
  const float normals[5][3] = {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}, {0, 0, -1}, {0, 1, 0}};
  for (int i = 0; i < 5; ++i) {
    m.add_vertex({coords[i][0], coords[i][1], coords[i][2]});
    m.nx.push_back(normals[i][0]), m.ny.push_back(normals[i][1]), m.nz.push_back(normals[i][2]);
    m.u.push_back(0.125f * float(i)), m.v.push_back(1 - 0.3f * float(i));
  }
  m.add_triangle(0, 1, 2);
  m.add_triangle(2, 3, 4);
  m.add_triangle(4, 1, 0);
  const std::string path = (dir.path / "out.ply").string();
  write_ply(m, path);
  const TriangleMesh r = read_ply(path);
  CHECK(r.x == m.x);
  CHECK(r.y == m.y);
  CHECK(r.z == m.z);
  CHECK(r.nx == m.nx);
  CHECK(r.ny == m.ny);
  CHECK(r.nz == m.nz);
  CHECK(r.u == m.u);
  CHECK(r.v == m.v);
  CHECK(r.indices == m.indices);
  // Without normals and uvs the file has none either.
  TriangleMesh bare;
  bare.x = m.x, bare.y = m.y, bare.z = m.z, bare.indices = m.indices;
  write_ply(bare, path);
  const TriangleMesh rb = read_ply(path);
  CHECK(!rb.has_normals());
  CHECK(!rb.has_uvs());
  CHECK(rb.x == bare.x);
  CHECK(rb.indices == bare.indices);
}

TEST_CASE("PLY: write_ply to an unwritable path is one error naming the path", "[mesh_io][ply_write]") {
  TriangleMesh m = make_cube();
  const std::string msg = error_of([&] { write_ply(m, "/nonexistent-torte-dir/out.ply"); });
  CHECK(msg.starts_with("/nonexistent-torte-dir/out.ply: cannot be written ("));
  CHECK(msg.find('\n') == std::string::npos);
  TempDir dir("ply_write_dir");
  // A directory where the file should go: the temporary file is written, the rename fails, nothing is left.
  fs::create_directories(dir.path / "taken.ply");
  const std::string msg2 = error_of([&] { write_ply(m, (dir.path / "taken.ply").string()); });
  CHECK(msg2.find("cannot be written") != std::string::npos);
  CHECK(!fs::exists(dir.path / "taken.ply.tmp"));
}

namespace {
// This process's resident set in bytes (/proc/self/statm, second field, in pages).
uint64_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  uint64_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * uint64_t(sysconf(_SC_PAGESIZE));
}
}  // namespace

// Issue 25: read_ply hands the file's pages back as it parses, so a scan and its file are not held whole together.
TEST_CASE("FileBytes: reads the file exactly and release_before returns its pages", "[mesh_io][memory]") {
  TempDir dir("filebytes");
  std::string bytes(size_t(64) << 20, '\0');
  for (size_t i = 0; i < bytes.size(); i += 4096) bytes[i] = char('a' + (i >> 12) % 26);
  const std::string path = dir.write("big.bin", bytes);
  FileBytes file(path);
  REQUIRE(file.bytes() == bytes);  // every page touched: resident
  const uint64_t before = resident_bytes();
  file.release_before(file.bytes().data() + file.bytes().size());
  const uint64_t after = resident_bytes();
  CHECK(after + (uint64_t(48) << 20) <= before);  // the 64 MB came back (other allocations may move a little)
  file.release_before(file.bytes().data());       // going back is harmless
  CHECK(error_of([&] { FileBytes missing((dir.path / "none.bin").string()); }).find("cannot open") == 0);
}
