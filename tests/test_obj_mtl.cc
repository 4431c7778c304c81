// MTL statements read by the OBJ reader (Ks, Ns, Ni, d/Tr, Ka as Ke, maps and their options), warnings for
// unknown statements, errors for damaged values, and split_by_material.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "core/error.h"
#include "geometry/obj.h"

using namespace torte;
namespace fs = std::filesystem;

namespace {

struct Dir {
  fs::path path = fs::temp_directory_path() / ("torte_obj_mtl_" + std::to_string(getpid()));
  Dir() { fs::create_directories(path); }
  ~Dir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name, std::ios::binary) << text;
  }
};

const std::string kTwoTriangles = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";

}  // namespace

TEST_CASE("MTL: every honoured statement is read", "[obj_mtl]") {
  Dir dir;
  dir.write("m.mtl",
            "newmtl shiny\nKd 0.2 0.3 0.4\nKs 1 1 1\nNs 250\nNi 1.33\nTr 0.25\nmap_Bump -bm 0.5 h.png\n"
            "newmtl lamp\nKa 20 20 20\nillum 1\n"
            "newmtl dim\nKa 0.1 0.1 0.1\nd 0.5\nbump other.png\nmap_Ks spec.png\n");
  const ObjData d = parse_obj(kTwoTriangles + "mtllib m.mtl\nusemtl shiny\nf 1 2 3\nusemtl lamp\nf 2 4 3\n",
                              "t.obj", dir.path.string());
  REQUIRE(d.materials.size() == 3);
  const ObjMaterial& s = d.materials[0];
  CHECK(s.defined);
  CHECK(s.kd == Rgb(0.2f, 0.3f, 0.4f));
  CHECK(s.ks == Rgb(1));
  CHECK(s.ns == 250);
  CHECK(s.ni == Approx(1.33f));
  CHECK(s.d == 0.75f);
  CHECK(s.map_bump == (dir.path / "h.png").string());
  CHECK(s.bump_scale == 0.5f);
  CHECK(d.materials[1].ke == Rgb(20));  // Ka above 1 without Ke: a light
  CHECK(d.materials[2].ke.is_black());  // an ordinary ambient colour stays out
  CHECK(d.materials[2].d == 0.5f);
  CHECK(d.materials[2].map_bump == (dir.path / "other.png").string());
  CHECK(d.warnings.empty());  // illum and map_Ks are known and not used: no warning
}

TEST_CASE("MTL: unknown statements warn once per file, damaged values are errors", "[obj_mtl]") {
  Dir dir;
  dir.write("w.mtl", "newmtl a\nKdd 1 1 1\nKdd 2\nfoo\n");
  const ObjData d = parse_obj(kTwoTriangles + "mtllib w.mtl\nf 1 2 3\n", "t.obj", dir.path.string());
  REQUIRE(d.warnings.size() == 2);
  CHECK_THAT(d.warnings[0], Catch::Contains("w.mtl: line 2: unknown MTL statement 'Kdd' ignored"));
  CHECK_THAT(d.warnings[1], Catch::Contains("w.mtl: line 4: unknown MTL statement 'foo'"));
  auto error = [&](const std::string& mtl) {
    dir.write("e.mtl", mtl);
    try {
      parse_obj(kTwoTriangles + "mtllib e.mtl\nf 1 2 3\n", "t.obj", dir.path.string());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK_THAT(error("newmtl a\nNs x\n"), Catch::Contains("e.mtl: line 2: 'x' is not a number"));
  CHECK_THAT(error("newmtl a\nTr 1.5\n"), Catch::Contains("e.mtl: line 2: Tr must be in [0, 1]"));
  CHECK_THAT(error("newmtl a\nKs 1 1\n"), Catch::Contains("Ks needs 1 or 3 numbers"));
  CHECK_THAT(error("newmtl a\nNi nan\n"), Catch::Contains("Ni must be finite and non-negative"));
  CHECK_THAT(error("newmtl a\nbump -bm x h.png\n"), Catch::Contains("-bm needs a number, got 'x'"));
  CHECK_THAT(error("newmtl a\nmap_Kd\n"), Catch::Contains("map_Kd needs a file name"));
}

TEST_CASE("split_by_material: one mesh per material with only its vertices", "[obj_mtl]") {
  const ObjData d = parse_obj(kTwoTriangles + "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n"
                                              "f 1/1 2/2 3/3\nusemtl a\nf 2/2 4/4 3/3\nusemtl b\nf 1/1 2/2 4/4\n"
                                              "usemtl a\nf 1/1 4/4 3/3\n",
                              "t.obj", "");
  const std::vector<ObjPart> parts = split_by_material(d);
  REQUIRE(parts.size() == 3);
  CHECK(parts[0].material == -1);  // before any usemtl, in order of first use
  CHECK(d.materials[size_t(parts[1].material)].name == "a");
  CHECK(d.materials[size_t(parts[2].material)].name == "b");
  CHECK(parts[0].mesh.triangle_count() == 1);
  REQUIRE(parts[1].mesh.triangle_count() == 2);
  CHECK(parts[1].mesh.vertex_count() == 4);  // 2, 4, 3 and then 1
  CHECK(parts[2].mesh.vertex_count() == 3);
  // Every triangle keeps its corners' positions and uvs.
  std::multiset<std::tuple<float, float, float, float>> in, out;
  for (size_t i = 0; i < d.mesh.indices.size(); ++i) {
    const uint32_t v = d.mesh.indices[i];
    in.insert({d.mesh.x[v], d.mesh.y[v], d.mesh.u[v], d.mesh.v[v]});
  }
  for (const ObjPart& p : parts) {
    REQUIRE(p.mesh.has_uvs());
    for (uint32_t v : p.mesh.indices) out.insert({p.mesh.x[v], p.mesh.y[v], p.mesh.u[v], p.mesh.v[v]});
  }
  CHECK(in == out);
}
