// glTF materials through the built binary: images embedded as data: URIs and as buffer views of a .glb, the
// base colour texture times its factor, and the metallic-roughness image's channels (G roughness, B metalness).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gltf_test_files.h"
#include "test_support.h"

using namespace torte::test;

namespace {

Result run(const TempDir& dir, const std::vector<std::string>& args) {
  return run_torte(dir, args, 60, dir.path.string());
}

std::string solid_png(uint8_t r, uint8_t g, uint8_t b) {
  std::vector<uint8_t> px;
  for (int i = 0; i < 4 * 4; ++i) px.insert(px.end(), {r, g, b});
  return png_rgb(4, 4, px);
}

// The quad's material "red" with `material` JSON (replacing its pbrMetallicRoughness) and `images` (JSON array
// entries); the point light is left out of the scene so the script lights the quad.
Gltf textured(Gltf g, const std::string& material, const std::string& images, int textures) {
  const std::string old_material = R"("pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.05, 0.05, 1],
                "metallicFactor": 0, "roughnessFactor": 1})";
  const size_t at = g.json.find(old_material);
  REQUIRE(at != std::string::npos);
  g.json.replace(at, old_material.size(), material);
  g.json.replace(g.json.find("[0, 2, 3]"), 9, "[0, 2]");
  std::string tex;
  for (int i = 0; i < textures; ++i) tex += std::string(i ? ", " : "") + "{\"source\": " + std::to_string(i) + "}";
  g.json.replace(g.json.find("\"meshes\":"), 0, "\"textures\": [" + tex + "], \"images\": [" + images + "],\n ");
  return g;
}

// Appends `bytes` to the .glb's buffer as buffer view 4; returns its image entry.
std::string add_buffer_image(Gltf& g, const std::string& bytes) {
  const size_t offset = g.bin.size();
  g.bin += bytes;
  while (g.bin.size() % 4) g.bin += '\0';
  const std::string old_length = "\"byteLength\": " + std::to_string(offset) + "}]";
  const size_t at = g.json.find(old_length);
  REQUIRE(at != std::string::npos);
  g.json.replace(at, old_length.size(), "\"byteLength\": " + std::to_string(g.bin.size()) + "}]");
  const std::string views_end = R"("byteLength": 12}],)";  // the index view of 6 unsigned shorts closes the list
  const size_t v = g.json.find(views_end);
  REQUIRE(v != std::string::npos);
  g.json.replace(v, views_end.size(), "\"byteLength\": 12}, {\"buffer\": 0, \"byteOffset\": " + std::to_string(offset) +
                                           ", \"byteLength\": " + std::to_string(bytes.size()) + "}],");
  return R"({"bufferView": 4, "mimeType": "image/png"})";
}

// Renders the file's quad through its camera; prints the middle pixel's r g b. `light` is Lua adding lights.
std::string middle_pixel(const TempDir& dir, const std::string& file, const std::string& light) {
  const std::string script = dir.write("probe.lua", "local g = torte.gltf.load('" + file + R"(')
local scene = torte.scene()
scene:add(torte.instance{group = g.group})
)" + light + R"(
local img = torte.render{scene = scene, camera = g.cameras[1], width = 16, height = 16, spp = 64}
local r, gr, b = img:pixel(8, 8)
print(("%.4f %.4f %.4f"):format(r, gr, b))
)");
  const Result r = run(dir, {"--quiet", script});
  INFO(r.err);
  REQUIRE(r.code == 0);
  return r.out;
}

std::vector<double> rgb_of(const std::string& line) {
  std::vector<double> v(3);
  std::sscanf(line.c_str(), "%lf %lf %lf", &v[0], &v[1], &v[2]);
  return v;
}

}  // namespace

TEST_CASE("gltf materials: embedded base colour images (data: URI and .glb buffer view) times the factor", "[gltf]") {
  TempDir dir("gltf_mat", "embedded");
  const std::string green = solid_png(0, 255, 0);
  // White base factor: the texture's green. A factor of (1, 0.5, 1) halves it.
  const std::string mat = R"("pbrMetallicRoughness": {"baseColorFactor": [1, @, 1, 1], "baseColorTexture": {"index": 0},
                "metallicFactor": 0, "roughnessFactor": 1})";
  auto with_factor = [&](const char* f) {
    std::string m = mat;
    m.replace(m.find('@'), 1, f);
    return m;
  };
  const std::string sky = "scene:add(torte.light.infinite{radiance = 1})";
  const Gltf data_uri = textured(make(5123, "data:application/octet-stream;base64," + base64(make(5123, "x").bin)),
                                 with_factor("1"), "{\"uri\": \"data:image/png;base64," + base64(green) + "\"}", 1);
  dir.write("data_uri.gltf", data_uri.json);
  Gltf in_glb = make(5123, "");
  const std::string image = add_buffer_image(in_glb, green);
  in_glb = textured(in_glb, with_factor("1"), image, 1);
  dir.write("buffer_view.glb", glb(in_glb));
  Gltf half = make(5123, "");
  const std::string half_image = add_buffer_image(half, green);  // before `half` is copied into textured()
  half = textured(half, with_factor("0.5"), half_image, 1);
  dir.write("half.glb", glb(half));
  for (const char* file : {"data_uri.gltf", "buffer_view.glb"}) {
    INFO(file);
    const std::vector<double> c = rgb_of(middle_pixel(dir, file, sky));
    CHECK(c[1] > 0.3);           // green diffuse under the white sky (plus the coat's white reflection)
    CHECK(c[1] > 3 * c[0]);
    CHECK(c[1] > 3 * c[2]);
  }
  // The green texture times (1, 0.5, 1) is the untextured base colour (0, 0.5, 0).
  Gltf plain = make(5123, "");
  plain.json.replace(plain.json.find("[0.8, 0.05, 0.05, 1]"), 20, "[0, 0.5, 0, 1]");
  plain.json.replace(plain.json.find("[0, 2, 3]"), 9, "[0, 2]");
  dir.write("plain.glb", glb(plain));
  const std::vector<double> halved = rgb_of(middle_pixel(dir, "half.glb", sky));
  const std::vector<double> expected = rgb_of(middle_pixel(dir, "plain.glb", sky));
  for (int c = 0; c < 3; ++c) CHECK(halved[c] == Approx(expected[c]).epsilon(0.05).margin(0.005));
}

TEST_CASE("gltf materials: the metallic-roughness image's B channel is metalness and G roughness", "[gltf]") {
  TempDir dir("gltf_mat", "metal");
  // A light from the upper left at 45 degrees and no environment: a mirror-smooth metal sends it away from the
  // camera (black), a dielectric scatters it back (its base colour).
  const std::string light = "scene:add(torte.light.directional{direction = {1, 0, -1}, irradiance = 3})";
  const std::string mat = R"("pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1],
                "metallicRoughnessTexture": {"index": 0}, "metallicFactor": @, "roughnessFactor": 1})";
  auto file = [&](const char* name, uint8_t g, uint8_t b, const char* factor) {
    Gltf q = make(5123, "");
    std::string m = mat;
    m.replace(m.find('@'), 1, factor);
    const std::string image = add_buffer_image(q, solid_png(0, g, b));
    q = textured(q, m, image, 1);
    dir.write(name, glb(q));
  };
  file("smooth_metal.glb", 0, 255, "1");       // roughness 0, metal
  file("smooth_plastic.glb", 0, 0, "1");       // roughness 0, metalness 0 from the image despite the factor
  file("metal_factor_off.glb", 0, 255, "0");   // the image's 1 times a factor of 0
  const double metal = rgb_of(middle_pixel(dir, "smooth_metal.glb", light))[0];
  const double plastic = rgb_of(middle_pixel(dir, "smooth_plastic.glb", light))[0];
  const double factor_off = rgb_of(middle_pixel(dir, "metal_factor_off.glb", light))[0];
  CHECK(metal < 0.01);
  CHECK(plastic > 0.2);
  CHECK(factor_off == Approx(plastic).epsilon(0.1));
  // Roughness from G: a rough metal scatters some of the light back to the camera.
  file("rough_metal.glb", 255, 255, "1");
  CHECK(rgb_of(middle_pixel(dir, "rough_metal.glb", light))[0] > 10 * std::max(metal, 1e-4));
}

TEST_CASE("gltf materials: the normal texture tilts the shading normal, its scale the tilt", "[gltf]") {
  TempDir dir("gltf_mat", "normal");
  const std::string light = "scene:add(torte.light.directional{direction = {0, 0, -1}, irradiance = 3})";
  // (0.5 + 0.5 sin 60, 0.5, 0.5 + 0.5 cos 60): the normal turned 60 degrees towards +u.
  const std::string tilted_png = solid_png(236, 128, 191);
  auto file = [&](const char* name, const char* normal) {
    Gltf q = make(5123, "");
    const std::string image = add_buffer_image(q, tilted_png);
    q = textured(q, std::string(R"("pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1],
                "metallicFactor": 0, "roughnessFactor": 1})") + normal, image, 1);
    dir.write(name, glb(q));
  };
  file("flat.glb", "");
  file("tilted.glb", R"(, "normalTexture": {"index": 0})");
  file("unscaled.glb", R"(, "normalTexture": {"index": 0, "scale": 0})");
  const double flat = rgb_of(middle_pixel(dir, "flat.glb", light))[0];
  const double tilted = rgb_of(middle_pixel(dir, "tilted.glb", light))[0];
  const double unscaled = rgb_of(middle_pixel(dir, "unscaled.glb", light))[0];
  CHECK(flat > 0.2);
  CHECK(tilted < 0.75 * flat);  // about cos 60 of the diffuse part
  CHECK(tilted > 0.2 * flat);
  CHECK(unscaled == Approx(flat).epsilon(0.02));
}

TEST_CASE("gltf materials: alphaMode MASK cuts out below alphaCutoff, BLEND is present with probability alpha", "[gltf]") {
  TempDir dir("gltf_mat", "alpha");
  const std::string sky = "scene:add(torte.light.infinite{radiance = 1})";
  auto file = [&](const char* name, const std::string& extra) {
    Gltf q = make(5123, "");
    q.json.replace(q.json.find("[0.8, 0.05, 0.05, 1]"), 20, "[0.8, 0.05, 0.05, 0.2]");
    q.json.replace(q.json.find("[0, 2, 3]"), 9, "[0, 2]");
    q.json.replace(q.json.find("\"name\": \"red\","), 14, "\"name\": \"red\"," + extra);
    dir.write(name, glb(q));
  };
  file("opaque.glb", "");                                   // alphaMode OPAQUE: alpha is ignored
  file("mask.glb", R"( "alphaMode": "MASK",)");             // 0.2 < the default cutoff 0.5: cut out
  file("mask_low.glb", R"( "alphaMode": "MASK", "alphaCutoff": 0.1,)");
  file("blend.glb", R"( "alphaMode": "BLEND",)");
  const double opaque = rgb_of(middle_pixel(dir, "opaque.glb", sky))[1];
  const double mask = rgb_of(middle_pixel(dir, "mask.glb", sky))[1];
  const double mask_low = rgb_of(middle_pixel(dir, "mask_low.glb", sky))[1];
  const double blend = rgb_of(middle_pixel(dir, "blend.glb", sky))[1];
  CHECK(opaque < 0.5);                           // the red quad's green under the white sky
  CHECK(mask == Approx(1).epsilon(0.01));        // the sky through the cut-out
  CHECK(mask_low == Approx(opaque).epsilon(0.02));
  CHECK(blend == Approx(0.2 * opaque + 0.8).epsilon(0.05));
}

TEST_CASE("gltf materials: the emissive texture times the factor is the area light's radiance", "[gltf]") {
  TempDir dir("gltf_mat", "emissive");
  Gltf q = make(5123, "");
  const std::string image = add_buffer_image(q, solid_png(0, 255, 0));
  q = textured(q, R"("pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0,
                "roughnessFactor": 1}, "emissiveFactor": [2, 2, 2], "emissiveTexture": {"index": 0})", image, 1);
  dir.write("emissive.glb", glb(q));
  const std::string script = dir.write("emissive.lua", R"(
local g = torte.gltf.load('emissive.glb')
local scene = torte.scene()
for _, e in ipairs(g.emitters) do scene:add(e) end
local img = torte.render{scene = scene, camera = g.cameras[1], width = 16, height = 16, spp = 4}
local r, gr, b = img:pixel(8, 8)
print(("%d %.4f %.4f %.4f"):format(#g.emitters, r, gr, b))
)");
  const Result r = run(dir, {"--quiet", script});
  INFO(r.err);
  REQUIRE(r.code == 0);
  int emitters = 0;
  double c[3] = {0, 0, 0};
  std::sscanf(r.out.c_str(), "%d %lf %lf %lf", &emitters, &c[0], &c[1], &c[2]);
  CHECK(emitters == 1);
  CHECK(c[0] == Approx(0).margin(1e-4));
  CHECK(c[1] == Approx(2).epsilon(1e-3));  // the green texel times the factor 2
  CHECK(c[2] == Approx(0).margin(1e-4));
}

// A real file: Blender (Debian's, where installed) exports Keenan Crane's Spot with its texture embedded in the
// .glb, a camera and a point light; torte loads all three and renders the file directly without a warning, and
// the cow is lit as in Blender (its watts became candela at 683 lm/W, which the loader turns back).
TEST_CASE("gltf materials: a Blender export with an embedded texture, a camera and a light", "[gltf][blender]") {
  const std::string spot = std::string(TORTE_SOURCE_DIR) + "/../shared/data/meshes/spot";
  if (!std::filesystem::exists("/usr/bin/blender") || !std::filesystem::exists(spot + "/spot_triangulated.obj")) {
    WARN("skipped: needs /usr/bin/blender (install-deps.sh --cycles) and " << spot);
    return;
  }
  TempDir dir("gltf_mat", "blender");
  const std::string py = dir.write("export.py", R"(import bpy, sys
spot = sys.argv[sys.argv.index("--") + 1]
out = sys.argv[sys.argv.index("--") + 2]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.obj(filepath=spot + "/spot_triangulated.obj")
for m in bpy.data.materials:
    nt = m.node_tree
    img = nt.nodes.new("ShaderNodeTexImage")
    img.image = bpy.data.images.load(spot + "/spot_texture.png")
    nt.links.new(img.outputs["Color"], nt.nodes.get("Principled BSDF").inputs["Base Color"])
cam = bpy.data.objects.new("cam", bpy.data.cameras.new("cam"))
cam.location = (0, -6, 1)
cam.rotation_euler = (1.45, 0, 0)
bpy.context.scene.collection.objects.link(cam)
lamp = bpy.data.objects.new("lamp", bpy.data.lights.new("lamp", "POINT"))
lamp.location = (2, -3, 3)
lamp.data.energy = 500
bpy.context.scene.collection.objects.link(lamp)
bpy.ops.export_scene.gltf(filepath=out, export_format="GLB", export_cameras=True, export_lights=True)
)");
  const std::string glb_path = dir / "spot.glb";
  const std::string cmd = "timeout 120 /usr/bin/blender -b --factory-startup --python '" + py + "' -- '" + spot +
                          "' '" + glb_path + "' > '" + (dir / "blender.log") + "' 2>&1";
  REQUIRE(std::system(cmd.c_str()) == 0);
  REQUIRE(std::filesystem::exists(glb_path));
  const std::string script = dir.write("check.lua", R"(
local g = torte.gltf.load("spot.glb")
assert(#g.cameras == 1 and #g.lights == 1, ("%d cameras, %d lights"):format(#g.cameras, #g.lights))
local scene = torte.scene():add(torte.instance{group = g.group})
local img = torte.render{scene = scene, camera = g.cameras[1], width = 48, height = 36, spp = 16}
-- The textured cow: white patches and black spots under the lamp, none of it blown out, black sky around.
local lo, hi, lit = math.huge, 0, 0
for y = 0, 35 do for x = 0, 47 do
  local r, gr, b = img:pixel(x, y)
  local v = (r + gr + b) / 3
  if v > 0.005 then lit = lit + 1; lo = math.min(lo, v); hi = math.max(hi, v) end
end end
print(("%d %.4f %.4f"):format(lit, lo, hi))
)");
  const Result r = run(dir, {"--quiet", script});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());  // no warning: the embedded texture was read
  int lit = 0;
  double lo = 0, hi = 0;
  std::sscanf(r.out.c_str(), "%d %lf %lf", &lit, &lo, &hi);
  CHECK(lit > 100);     // the cow covers a good part of the frame
  CHECK(hi < 2.0);      // lit as in Blender, not thousands of times too bright
  CHECK(hi > 0.2);
  CHECK(lo < 0.3 * hi);  // the texture's dark spots
  const Result view = run(dir, {"--quiet", "spot.glb", "width=32", "height=24", "spp=2", "-o", "view.png"});
  INFO(view.err);
  CHECK(view.code == 0);
  CHECK(std::filesystem::exists(dir.path / "view.png"));
}
