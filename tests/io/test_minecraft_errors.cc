// Errors met while decoding a chunk are one line naming the region file and the chunk: values of the wrong NBT
// type anywhere in real chunks (structural mutations, re-encoded and loaded), skipped chunks' messages, and the
// formatting of errors that do not come from the loader's own checks. The catalogue (tests/bad_inputs/minecraft)
// has one case per kind of damage.
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "minecraft_support.h"

using namespace torte::test;
using namespace torte::test::minecraft;

namespace {

// Re-encodes decoded chunks as NBT after replacing 1-3 values (picked in sorted key order from a fixed-seed
// generator, so every run makes the same mutants) with values of other types, stores them uncompressed in a
// region of their own and loads it. Prints "loaded N errors M", and every error that does not name the chunk,
// holds a line break or is a Lua error of the decoder itself ("(in minecraft.world:12)") as "BAD <message>".
constexpr char kMutateScript[] = R"LUA(
local region = require "minecraft.region"
local world = require "minecraft.world"
local P = string.pack
local function sorted(t)
  local keys = {}
  for k in pairs(t) do keys[#keys + 1] = k end
  table.sort(keys, function(a, b)
    if type(a) == type(b) then return a < b end
    return type(a) == "number"
  end)
  return keys
end
local function encode(v)  -- a decoded value -> {tag type, payload}
  if math.type(v) == "integer" then
    if v >= -0x80000000 and v <= 0x7fffffff then return {3, P(">i4", v)} end
    return {4, P(">i8", v)}
  end
  if type(v) == "number" then return {6, P(">d", v)} end
  if type(v) == "string" then
    if #v < 65535 and not v:find("[%z\1-\31\128-\255]") then return {8, P(">s2", v)} end
    return {7, P(">i4", #v) .. v}
  end
  if type(v) == "userdata" then
    local out = {P(">i4", #v)}
    for _, x in ipairs(v:table()) do out[#out + 1] = P(">i8", x) end
    return {12, table.concat(out)}
  end
  if #v > 0 or next(v) == nil then  -- a list: items of another type than the first become copies of it
    local items = {}
    for i, x in ipairs(v) do items[i] = encode(x) end
    local t = items[1] and items[1][1] or 0
    local out = {P(">Bi4", t, #items)}
    for _, item in ipairs(items) do out[#out + 1] = (item[1] == t and item or items[1])[2] end
    return {9, table.concat(out)}
  end
  local out = {}
  for _, k in ipairs(sorted(v)) do
    local e = encode(v[k])
    out[#out + 1] = P("B", e[1]) .. P(">s2", tostring(k)) .. e[2]
  end
  return {10, table.concat(out) .. "\0"}
end
local function copy(t)
  if type(t) ~= "table" then return t end
  local o = {}
  for k, v in pairs(t) do o[k] = copy(v) end
  return o
end
local function slots(t, out)  -- every (table, key) below t
  for _, k in ipairs(sorted(t)) do
    out[#out + 1] = {t, k}
    if type(t[k]) == "table" then slots(t[k], out) end
  end
  return out
end
local state = 12345
local function rand(n)
  state = (state * 1103515245 + 12345) & 0x7fffffff
  return state % n + 1
end
local others = {7, -1, 1e300, "x", {}, {1, 2, 3}, {a = 1}, ("\0"):rep(4096), 0x7fffffff, -129, {"a", "b"}}
local loaded, errors = 0, 0
for world_name in torte.args.worlds:gmatch("[^,]+") do
  local r = region.open(world.region_files(torte.args.data .. "/" .. world_name)[1])
  local chunks = r:chunks()
  for _ = 1, tonumber(torte.args.mutants) do
    local c = chunks[rand(#chunks)]
    local root = copy(r:read(c))
    local all = slots(root, {})
    for _ = 1, rand(3) do
      local s = all[rand(#all)]
      s[1][s[2]] = copy(others[rand(#others)])
    end
    local bytes = P("B", 10) .. P(">s2", "") .. encode(root)[2]
    local name = ("r.%d.%d.mca"):format(r.rx, r.rz)
    local header = {}
    for i = 0, 1023 do header[#header + 1] = P(">I4", i == c.index and (2 << 8 | (#bytes + 4100) // 4096) or 0) end
    local f = assert(io.open(name, "wb"))
    f:write(table.concat(header), ("\0"):rep(4096), P(">I4B", #bytes + 1, 3), bytes)
    f:close()
    local ok, err = pcall(world.load, {files = {name}, emitters = true, probes = {{c.x * 16 + 3, 70, c.z * 16 + 5}}})
    if ok then
      loaded = loaded + 1
    else
      errors = errors + 1
      local chunk = ("%s: chunk (%d, %d) "):format(name, c.x, c.z)
      if err:sub(1, #chunk) ~= chunk or err:find("\n") or err:find("(in minecraft.", 1, true) then
        print("BAD " .. err)
      end
    end
  end
end
print(("loaded %d errors %d"):format(loaded, errors))
print("ok")
)LUA";

}  // namespace

TEST_CASE("minecraft errors: values of the wrong NBT type anywhere in real chunks are one line naming the chunk",
          "[minecraft]") {
  if (!have_worlds()) return;
  McDir dir("mutated");
  const std::string out =
      run_ok(dir, kMutateScript,
             {"data=" + kWorlds.string(), "mutants=120",
              "worlds=prismarine-1.8.9,prismarine-1.12.2,prismarine-1.14.4,prismarine-1.16,querz-nbt-1.18.2,"
              "bluenbt-1.20.1-paper"});
  INFO(out);
  CHECK_THAT(out, !Catch::Contains("BAD "));
  int loaded = 0, errors = 0;
  const std::vector<std::string> lines = lines_of(out);
  REQUIRE(lines.size() >= 2);
  REQUIRE(std::sscanf(lines[lines.size() - 2].c_str(), "loaded %d errors %d", &loaded, &errors) == 2);
  CHECK(loaded + errors == 720);
  CHECK(errors > 100);  // the mutations reach what the decoder reads
  CHECK(loaded > 100);  // and what it ignores
}

TEST_CASE("minecraft errors: a skipped chunk's message names the chunk, and the other chunks load", "[minecraft]") {
  McDir dir("skipped");
  const std::string out = run_ok_with_writer(dir, R"LUA(
local P = string.pack
local function chunk(cx, cz, palette)
  local section = W.compound{W.tag(1, "Y", P(">i1", 4)), W.tag(9, "Palette", palette),
                             W.tag(12, "BlockStates", P(">i4", 256) .. ("\0"):rep(2048))}
  local level = W.tag(10, "Level", W.compound{W.tag(3, "xPos", P(">i4", cx)), W.tag(3, "zPos", P(">i4", cz)),
                                              W.tag(8, "Status", P(">s2", "full")),
                                              W.tag(9, "Sections", P(">Bi4", 10, 1) .. section)})
  return W.tag(10, "", W.compound{level, W.tag(3, "DataVersion", P(">i4", 2566))})
end
local stone = P(">Bi4", 10, 1) .. W.compound{W.tag(8, "Name", P(">s2", "minecraft:stone"))}
local ints = P(">Bi4", 3, 2) .. P(">i4i4", 1, 2)  -- a palette of ints
W.region("r.0.0.mca", {{0, 0, chunk(0, 0, stone)}, {1, 0, chunk(1, 0, ints)}, {2, 0, chunk(2, 0, stone)}}, 3)
local st = require("minecraft.world").load{dir = ".", skip_bad_chunks = true}
print(st.full, st.bad, st.non_air)
print(st.bad_messages[1])
local ok, err = pcall(require("minecraft.world").load, {dir = "."})
print(err)
print("ok")
)LUA");
  const std::vector<std::string> lines = lines_of(out);
  REQUIRE(lines.size() == 4);
  CHECK(lines[0] == "2\t1\t8192");
  const std::string expected =
      "./r.0.0.mca: chunk (1, 0) (entry 1,0 of the region), section Y=4: palette entry 1 is a number, not a compound";
  CHECK(lines[1] == expected);
  CHECK(lines[2] == expected);
}

TEST_CASE("minecraft errors: errors from outside the loader's checks get the chunk prefix", "[minecraft]") {
  McDir dir("prefix");
  const std::string out = run_ok(dir, R"LUA(
local region = require "minecraft.region"
local where = "w/r.0.0.mca: chunk (1, 2) (entry 1,2 of the region)"
for _, e in ipairs({
  where .. ": section 1 has no Y",                                         -- the loader's own: unchanged
  "[torte] minecraft.world:150: attempt to index a number value (local 'e')",  -- a decoder bug
  "[torte] minecraft.world:99: torte.data.map_int16: the string has an odd length (3)",  -- a binding
  "scene.lua:7: the sink failed",                                          -- the caller's sink
  {},                                                                       -- not even a string
}) do
  print((region.chunk_error(e, where):gsub("table: 0x%x+", "table")))
end
print("ok")
)LUA");
  const std::vector<std::string> lines = lines_of(out);
  REQUIRE(lines.size() == 6);
  const std::string w = "w/r.0.0.mca: chunk (1, 2) (entry 1,2 of the region): ";
  CHECK(lines[0] == w + "section 1 has no Y");
  CHECK(lines[1] == w + "attempt to index a number value (local 'e') (in minecraft.world:150)");
  CHECK(lines[2] == w + "torte.data.map_int16: the string has an odd length (3)");
  CHECK(lines[3] == w + "scene.lua:7: the sink failed");
  CHECK(lines[4] == w + "table");
}
