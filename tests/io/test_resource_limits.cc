// Resource bounds of the file readers that need OpenImageIO or the Lua bindings (issue 22): image textures and
// environment maps checked from their headers before their pixels are allocated, truncated images found when the
// texture is made (and, for tiles read later, by the render, which then fails naming the file), and the output
// limit of torte.data.inflate / gunzip. The bad-input catalogue (tests/bad_inputs/*/rl_*.lua) covers the one-line
// messages of each format through the binary; these check what it cannot see.
#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <functional>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/memory_budget.h"
#include "../error_helpers.h"
#include "film/image_io.h"
#include "runtime.h"
#include "test_support.h"
#include "texture/image_texture_oiio.h"

using namespace torte;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

using test::error_of;
using test::ScopedMemoryLimit;

struct LimitDir : test::TempDir {
  explicit LimitDir(const std::string& name) : test::TempDir("limits", name) {}
};

// A 512x512 checker in 64x64 tiles, as a tiled half-float EXR (the image cache reads it a tile at a time).
void write_tiled_exr(const std::string& path) {
  OIIO::ImageSpec spec(512, 512, 3, OIIO::TypeDesc::HALF);
  spec.tile_width = spec.tile_height = 64;
  std::vector<float> pixels(512 * 512 * 3);
  for (int y = 0; y < 512; ++y)
    for (int x = 0; x < 512; ++x)
      for (int c = 0; c < 3; ++c) pixels[(size_t(y) * 512 + x) * 3 + c] = ((x / 32 + y / 32) % 2) ? 0.9f : 0.1f;
  auto out = OIIO::ImageOutput::create(path);
  REQUIRE(out);
  REQUIRE(out->open(path, spec));
  REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
  REQUIRE(out->close());
}

void cut_file(const std::string& from, const std::string& to, double fraction) {
  fs::copy_file(from, to, fs::copy_options::overwrite_existing);
  fs::resize_file(to, uintmax_t(double(fs::file_size(from)) * fraction));
}

const char* kTexturedSphere = R"LUA(
local t = torte.texture.image{file = torte.args.file}
local s = torte.scene()
s:add(torte.shape.sphere{radius = 1, material = torte.material.matte{color = t}})
s:add(torte.light.point{position = {0, 2, -4}, intensity = {20, 20, 20}})
local img = torte.render{scene = s, camera = torte.camera.perspective{eye = {0, 0, -2.2}, look_at = {0, 0, 0}},
                         width = 48, height = 48, spp = 2}
print(img:mean())
)LUA";

}  // namespace

TEST_CASE("limits io: a tiled texture whose later tiles are cut fails the render, naming the file", "[limits]") {
  LimitDir dir("tiled");
  const std::string good = dir / "good.exr", cut = dir / "cut.exr";
  write_tiled_exr(good);
  cut_file(good, cut, 0.66);  // the tiles of the middle rows (read when the texture is made) survive
  const std::string script = dir.write("scene.lua", kTexturedSphere);
  // The intact file renders; the cut one is accepted when made (its middle tile reads) and fails while rendering.
  test::Result ok = test::run_torte(dir, {"--quiet", script, "file=good.exr"}, 60, dir.path.string());
  test::check_no_crash(ok);
  CHECK(ok.code == 0);
  test::Result bad = test::run_torte(dir, {"--quiet", script, "file=cut.exr"}, 60, dir.path.string());
  const std::string line = test::check_error(bad);
  // OpenImageIO keeps its error text per thread, so the reason is its own when the failing read ran on the thread
  // that asks, and torte's generic one otherwise; either way the line names the file and the render call.
  CHECK_THAT(line, Contains("scene.lua:") && Contains(": cannot read image texture 'cut.exr' while rendering: ") &&
                       (Contains("Unexpected end of file") || Contains("the pixel data is truncated or corrupt")));
  CHECK(bad.out.empty());  // no mean printed: the render did not return an image
}

TEST_CASE("limits io: a truncated texture fails every time it is made, not only the first", "[limits]") {
  LimitDir dir("again");
  const std::string good = dir / "good.png", cut = dir / "cut.png";
  Image img(256, 256);
  for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = Rgb(float(i % 251) / 251, float(i % 13) / 13, 0.5f);
  write_image(img, good);
  cut_file(good, cut, 0.5);
  for (int attempt = 0; attempt < 2; ++attempt) {
    INFO("attempt " << attempt);
    CHECK_THAT(error_of([&] { open_image_texture(cut, {}); }),
               Contains("cannot read image texture '" + cut + "': the pixel data is truncated or corrupt"));
  }
  CHECK(open_image_texture(good, {})->description() == good + " (256x256, sRGB)");
}

TEST_CASE("limits io: image sizes from the header are checked against the budget before reading", "[limits]") {
  LimitDir dir("budget");
  // Headers only: 4096x4096 RGB, as a texture 18 bytes a texel (the cached tile, the reader's buffer, a float
  // copy) plus a third for MIP levels, 384 MB; as an image 400 MB decoded as floats.
  const std::string ppm = dir.write("big.ppm", "P6\n4096 4096\n255\n" + std::string(1000, '\x40'));
  ScopedMemoryLimit limit(uint64_t(32) << 20);
  CHECK_THAT(error_of([&] { open_image_texture(ppm, {}); }),
             Contains("image texture '" + ppm + "' (4096x4096, 3 channels) needs ~384 MB") &&
                 Contains("over the memory limit of 32.0 MB"));
  CHECK_THAT(error_of([&] { read_image(ppm); }),
             Contains("image '" + ppm + "' (4096x4096, 3 channels) needs ~384 MB") &&
                 Contains("over the memory limit of 32.0 MB"));
}

TEST_CASE("limits io: inflate and gunzip stop at their output limit, exactly", "[limits]") {
  LimitDir dir("inflate");
  // 4128259 zero bytes as one fixed-Huffman deflate block (see tests/bad_inputs/bombs/rl_zlib_bomb_1gib.lua),
  // with zlib's and gzip's trailers computed by zlib itself through a first unbounded call.
  const std::string script = dir.write("inflate.lua", R"LUA(
local D = torte.data
local raw = "\x63\x18\x05" .. ("\xa3\x60\x14\x8c\x82\x51\x30\x0a\x46\xc1\x28\x18\x05"):rep(2000) .. "\x00"
local n = 1 + 258 * (1 + 8 * 2000)
-- Trailers: Adler-32 (zlib) and CRC-32 + length (gzip) of n zeros.
local a, b = 1, 0
for _ = 1, n do b = (b + a) % 65521 end
local z = "\x78\x01" .. raw .. string.pack(">I4", (b << 16) | a)
local table_ = {}
for i = 0, 255 do
  local c = i
  for _ = 1, 8 do c = (c >> 1) ~ (0xedb88320 & -(c & 1)) end
  table_[i] = c
end
local crc = 0xffffffff
for _ = 1, n do crc = (crc >> 8) ~ table_[crc & 0xff] end  -- a zero byte
local g = "\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03" .. raw .. string.pack("<I4I4", crc ~ 0xffffffff, n)
assert(#D.inflate(z) == n and #D.gunzip(g) == n, "the default limit lets 4 MB through")
assert(#D.inflate(z, n) == n and #D.gunzip(g, n) == n, "a limit of exactly the size")
local ok, e = pcall(D.inflate, z, n - 1)
assert(not ok and e:find("decompresses to more than 3.9 MB", 1, true), e)
ok, e = pcall(D.gunzip, g, 0)
assert(not ok and e:find("decompresses to more than 0 B", 1, true), e)
ok, e = pcall(D.inflate, z, "a lot")
assert(not ok and e:find("output limit must be a non-negative integer", 1, true), e)
assert(D.inflate("\x78\x9c\x03\x00\x00\x00\x00\x01", 0) == "", "an empty stream fits a limit of 0")
print("ok")
)LUA");
  test::Result r = test::run_torte(dir, {"--quiet", script}, 120, dir.path.string());
  test::check_no_crash(r);
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(r.out == "ok\n");
}

TEST_CASE("limits io: nbt refuses counts whose Lua tables would pass the memory budget", "[limits]") {
  LimitDir dir("nbt");
  // Counts the bytes can hold (an empty compound is one byte, an int four) but whose tables cost 16 to 80 bytes
  // an entry: run in this process, under a budget of what it holds now plus 24 MB.
  const std::string script = dir.write("nbt.lua", R"LUA(
local list = "\x09\x00\x01L\x0a" .. string.pack(">i4", 1000000) .. ("\0"):rep(1000000)
local ok, e = pcall(torte.data.nbt, list)
assert(not ok and e:find("an NBT list of 1000000 entries needs ~76.3 MB", 1, true), e)
local ints = "\x0b\x00\x01I" .. string.pack(">i4", 2000000) .. ("\0"):rep(8000000)
ok, e = pcall(torte.data.nbt, ints)
assert(not ok and e:find("an NBT int array of 2000000 entries needs ~30.5 MB", 1, true), e)
assert(#torte.data.nbt("\x09\x00\x01L\x0a" .. string.pack(">i4", 1000) .. ("\0"):rep(1000)) == 1000)
)LUA");
  ScopedMemoryLimit limit(resident_memory() + (uint64_t(24) << 20));
  lua::RunOptions options;
  options.script = script;
  options.quiet = true;
  CHECK(lua::run_script(options) == lua::kExitOk);
}
