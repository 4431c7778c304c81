// Shared by the Minecraft test files (test_minecraft_*.cc): temporary directories, the shared worlds, running
// Lua scripts through the built binary (TORTE_BINARY), and a Lua NBT / Anvil region writer for hand-made regions.
#pragma once
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "test_support.h"

namespace torte::test::minecraft {

struct McDir : TempDir {
  explicit McDir(const std::string& name) : TempDir("minecraft", name) {}
};

inline const std::filesystem::path kWorlds =
    std::filesystem::path(TORTE_SOURCE_DIR) / ".." / "shared" / "data" / "minecraft";

inline bool have_worlds() {
  if (std::filesystem::is_directory(kWorlds)) return true;
  WARN("skipped: " << kWorlds.string() << " is absent (../shared/data not installed)");
  return false;
}

// Writes `script` into `dir` and runs it with --quiet (in `dir`); returns the result.
inline Result run_lua(const McDir& dir, const std::string& script, const std::vector<std::string>& args = {},
               bool quiet = true, double timeout = 60) {
  const std::string path = dir.write("script.lua", script);
  std::vector<std::string> argv;
  if (quiet) argv.push_back("--quiet");
  argv.push_back(path);
  argv.insert(argv.end(), args.begin(), args.end());
  return run_torte(dir, argv, timeout, dir.path.string());
}

// Runs a script that must succeed and print "ok" last; returns stdout.
inline std::string run_ok(const McDir& dir, const std::string& script, const std::vector<std::string>& args = {}) {
  const Result r = run_lua(dir, script, args);
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  CHECK_THAT(r.out, Catch::EndsWith("ok\n"));
  return r.out;
}

// Lua helpers for the tests below: an NBT writer, an Anvil region writer and a 1.12-format chunk.
inline constexpr char kRegionWriter[] = R"LUA(
local P = string.pack
local W = {}
local function tag(t, n, payload) return P("B", t) .. P(">s2", n) .. payload end
W.tag = tag
function W.compound(fields) return table.concat(fields) .. "\0" end
-- A region file at `path` holding `chunks` ({lx, lz, payload bytes}) with compression byte `compression`.
function W.region(path, chunks, compression)
  local loc, body, sector = {}, {}, 2
  for _, c in ipairs(chunks) do
    local bytes = P(">I4B", #c[3] + 1, compression) .. c[3]
    local n = (#bytes + 4095) // 4096
    body[#body + 1] = bytes .. ("\0"):rep(n * 4096 - #bytes)
    loc[c[1] + 32 * c[2]] = (sector << 8) | n
    sector = sector + n
  end
  local h = {}
  for i = 0, 1023 do h[#h + 1] = P(">I4", loc[i] or 0) end
  for i = 0, 1023 do h[#h + 1] = P(">I4", 1700000000) end
  local f = assert(io.open(path, "wb"))
  f:write(table.concat(h), table.concat(body))
  f:close()
end
-- One pre-1.13 chunk (DataVersion 1343) at (cx, cz) with one section Y=4 (y 64..79): blocks {[{x, y, z}] = id}
-- in chunk-local coordinates (y 0..15 in the section) and a biome id per column from biome(x, z).
function W.legacy_chunk(cx, cz, blocks, biome)
  local b = {}
  for i = 1, 4096 do b[i] = 0 end
  for _, e in ipairs(blocks) do b[((e[2] * 16 + e[3]) * 16 + e[1]) + 1] = e[4] end
  local bytes = {}
  for i = 1, 4096 do bytes[i] = string.char(b[i]) end
  local cols = {}
  for z = 0, 15 do for x = 0, 15 do cols[#cols + 1] = string.char(biome(x, z)) end end
  local section = W.compound{tag(1, "Y", P(">i1", 4)), tag(7, "Blocks", P(">i4", 4096) .. table.concat(bytes)),
                             tag(7, "Data", P(">i4", 2048) .. ("\0"):rep(2048))}
  local level = tag(10, "Level", W.compound{tag(3, "xPos", P(">i4", cx)), tag(3, "zPos", P(">i4", cz)),
                                            tag(9, "Sections", P(">Bi4", 10, 1) .. section),
                                            tag(7, "Biomes", P(">i4", 256) .. table.concat(cols))})
  return tag(10, "", W.compound{level, tag(3, "DataVersion", P(">i4", 1343))})
end
return W
)LUA";

// `script` run with the writer above available as the local W (writer.lua in `dir`, found through package.path).
inline std::string run_ok_with_writer(const McDir& dir, const std::string& script,
                               const std::vector<std::string>& args = {}) {
  dir.write("writer.lua", kRegionWriter);
  return run_ok(dir, "package.path = \"./?.lua;\" .. package.path\nlocal W = require \"writer\"\n" + script, args);
}

}  // namespace torte::test::minecraft
