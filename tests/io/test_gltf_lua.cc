// torte.gltf.load through the built binary: files written here (indices of every component type, embedded and
// external buffers, .glb), the node hierarchy, materials, cameras, KHR_lights_punctual lights, and damaged files
// as one-line errors.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

using namespace torte::test;

namespace {

Result run(const TempDir& dir, const std::vector<std::string>& args) {
  return run_torte(dir, args, 60, dir.path.string());
}

std::string base64(const std::string& in) {
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
void put(std::string& b, T v) {
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
Gltf make(int index_type, const std::string& uri) {
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

std::string glb(const Gltf& g) {
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

const char kCheck[] = R"(
local g = torte.gltf.load(arg_file)
assert(#g.cameras == 1 and #g.lights == 1 and g.materials.red and g.materials.lamp, "objects")
local scene = torte.scene()
scene:add(torte.instance{group = g.group})
scene:add(torte.light.infinite{radiance = 1})
local img = torte.render{scene = scene, camera = g.cameras[1], width = 16, height = 16, spp = 16}
local centre, corner = img:pixel(8, 8), img:pixel(0, 0)
-- The quad (2 x 2 after its parent's scale) fills the middle of the view: red under the sky and the light.
assert(corner > 0.95 and corner < 1.05, "sky in the corner: " .. corner)
assert(centre < 0.8 * corner, "the quad in the middle: " .. centre)
print("ok")
)";

}  // namespace

TEST_CASE("gltf lua: every index type, embedded and external buffers, .glb", "[gltf]") {
  TempDir dir("gltf", "load");
  for (int type : {5121, 5123, 5125}) {
    INFO("index type " << type);
    const Gltf embedded = make(type, "data:application/octet-stream;base64," + base64(make(type, "x").bin));
    dir.write("embedded.gltf", embedded.json);
    const Gltf external = make(type, "quad.bin");
    dir.write("quad.bin", external.bin);
    dir.write("external.gltf", external.json);
    dir.write("quad.glb", glb(make(type, "")));
    for (const char* file : {"embedded.gltf", "external.gltf", "quad.glb"}) {
      INFO(file);
      const std::string script = dir.write("check.lua", std::string("local arg_file = '") + file + "'\n" + kCheck);
      const Result r = run(dir, {"--quiet", script});
      INFO("stderr: " << r.err);
      CHECK(r.code == 0);
      CHECK(r.out == "ok\n");
    }
  }
}

TEST_CASE("gltf lua: damaged files are one-line errors naming the file", "[gltf]") {
  TempDir dir("gltf", "damaged");
  const Gltf good = make(5123, "quad.bin");
  dir.write("quad.bin", good.bin);
  struct Case { const char* name; std::string json; const char* expect; };
  std::string past = good.json;
  past.replace(past.find("\"count\": 6"), 10, "\"count\": 60");
  std::string float_indices = good.json;
  float_indices.replace(float_indices.rfind("\"componentType\": 5123"), 21, "\"componentType\": 5122");  // signed short
  std::string bad_index = good.json;
  bad_index.replace(bad_index.find("\"indices\": 3"), 12, "\"indices\": 9");
  const Case cases[] = {
      {"truncated", good.json.substr(0, good.json.size() / 2), "bad.gltf"},
      {"past the end", past, "reaches past the end of its buffer"},
      {"signed indices", float_indices, "indices must be unsigned byte, short or int"},
      {"no accessor", bad_index, "bad.gltf"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    dir.write("bad.gltf", c.json);
    const std::string script = dir.write("bad.lua", "-- line 1\nlocal g = torte.gltf.load('bad.gltf')\n");
    const std::string line = check_error(run(dir, {script}));
    CHECK_THAT(line, Catch::Contains(script + ":2: torte.gltf.load"));
    CHECK_THAT(line, Catch::Contains(c.expect));
  }
  const std::string script = dir.write("missing.lua", "local g = torte.gltf.load('nothing.glb')\n");
  CHECK_THAT(check_error(run(dir, {script})), Catch::Contains("nothing.glb"));
}

// `torte model.glb`: the embedded viewer (lua/torte/view_model.lua) renders the file with its camera or a framing
// one, adds a light rig when the file has no light, and takes the shipped scenes' arguments.
TEST_CASE("gltf lua: torte model.glb renders the file directly", "[gltf]") {
  TempDir dir("gltf", "view");
  Gltf unlit = make(5123, "");
  // Without its point light the file has no light of its own: the viewer adds the sky and the sun.
  unlit.json.replace(unlit.json.find("[0, 2, 3]"), 9, "[0, 2]");
  dir.write("quad.glb", glb(make(5123, "")));
  dir.write("unlit.glb", glb(unlit));
  // The rendered image through a texture lookup: the quad's middle against the corner.
  const std::string probe = dir.write("probe.lua", R"(
local t = torte.texture.image{file = arg_file}
local function lum(u, v) local c = t:eval{uv = {u, v}} return c[1] + c[2] + c[3] end
print(("%.4f %.4f"):format(lum(0.5, 0.5), lum(0.02, 0.02)))
)");
  auto centre_and_corner = [&](const std::string& exr) {
    const std::string script = dir.write("run_probe.lua", "arg_file = '" + exr + "'\n" + read_file(probe));
    const Result r = run(dir, {"--quiet", script});
    INFO(r.err);
    REQUIRE(r.code == 0);
    double centre = 0, corner = 0;
    std::istringstream(r.out) >> centre >> corner;
    return std::pair{centre, corner};
  };
  {
    const Result r = run(dir, {"--quiet", "quad.glb", "width=24", "height=16", "spp=4", "output=file_camera.exr"});
    INFO(r.err);
    CHECK(r.code == 0);
    CHECK(std::filesystem::exists(dir.path / "file_camera.exr"));
    CHECK(std::filesystem::exists(dir.path / "file_camera.png"));
  }
  {  // camera=0 frames the model: the quad is in the middle, the sky in the corner
    const Result r = run(dir, {"--quiet", "unlit.glb", "camera=0", "width=24", "height=16", "spp=8", "output=framed.exr"});
    INFO(r.err);
    REQUIRE(r.code == 0);
    const auto [centre, corner] = centre_and_corner("framed.exr");
    CHECK(corner > 0);             // the viewer's sky: the file has no light
    CHECK(centre != Approx(corner).epsilon(0.05));  // something other than sky in the middle
  }
  {  // sky=off and no light of the file's own: black, and torte warns about it
    const Result r = run(dir, {"unlit.glb", "sky=off", "width=8", "height=8", "spp=1", "output=dark.exr"});
    CHECK(r.code == 0);
    CHECK_THAT(r.err, Catch::Contains("warning"));
  }
  CHECK_THAT(check_error(run(dir, {"quad.glb", "camera=3", "width=8", "height=8"})),
             Catch::Contains("has 1 camera"));
  CHECK_THAT(check_error(run(dir, {"quad.glb", "sky=maybe"})), Catch::Contains("argument 'sky' must be auto, on or off"));
  CHECK_THAT(check_error(run(dir, {"quad.glb", "spp=four"})), Catch::Contains("argument 'spp' must be a number"));
  dir.write("broken.glb", "glTF not really");
  CHECK_THAT(check_error(run(dir, {"broken.glb"})), Catch::Contains("broken.glb"));
  {
    const Result r = run(dir, {"--list-args", "quad.glb"});
    CHECK(r.code == 0);
    CHECK_THAT(r.out, Catch::Contains("sky_strength"));
  }
}
