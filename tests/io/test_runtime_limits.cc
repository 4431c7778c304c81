// The script runtime's defences, in process and on the built binary: userdata type tags that a swapped
// metatable cannot fool, text-only chunks, errors that always name the script's file and line, the Lua memory
// cap and instruction budget, the command line's ranges, and Ctrl-C stopping Lua code (lua/script_limits.h).
#include <catch2/catch.hpp>

#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <new>
#include <string>
#include <thread>
#include <vector>

#include "core/interrupt.h"
#include "runtime.h"
#include "script_limits.h"
#include "test_support.h"
#include "types.h"

namespace fs = std::filesystem;
using namespace torte::test;

namespace {

struct LimitsDir : TempDir {
  explicit LimitsDir(const std::string& name) : TempDir("limits", name) {}
};

// A Lua state with every standard library as luaL_openlibs gives it (the debug library unrestricted, as a fuzz
// harness has it) and the torte module: the type tags alone must keep the bindings safe here.
struct RawState {
  lua_State* L = luaL_newstate();
  torte::lua::RunContext ctx;
  RawState() {
    luaL_openlibs(L);
    torte::lua::set_run_context(L, &ctx);
    torte::lua::open_torte_module(L, torte::lua::RunOptions{});
  }
  ~RawState() { lua_close(L); }
  // Runs `code`; returns "" when it succeeds, else the error message.
  std::string run(const std::string& code) {
    if (luaL_dostring(L, code.c_str()) == LUA_OK) return "";
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "?";
    lua_pop(L, 1);
    return msg;
  }
};

int throws_bad_alloc(lua_State*) { throw std::bad_alloc(); }
int throws_interrupted(lua_State*) { throw torte::Interrupted("interrupted while building the scene"); }

// Runs the binary to the end in `dir` (the working directory).
Result run_in(const TempDir& dir, const std::vector<std::string>& args, double timeout = 60) {
  return run_torte(dir, args, timeout, dir.path.string());
}

}  // namespace

TEST_CASE("runtime: a torte object given another type's metatable is never read as that type", "[runtime]") {
  RawState s;
  // An NBT compound {l = long array [1, 2]} for a torte.data.longs.
  const std::string script = R"(
    local scene, shape = torte.scene(), torte.shape.sphere{}
    local longs = torte.data.nbt(string.pack(">I1 s2 I1 s2 i4 i8 i8 I1", 10, "", 12, "l", 2, 1, 2, 0)).l
    assert(#longs == 2)
    local scene_mt, longs_mt = debug.getmetatable(scene), debug.getmetatable(longs)
    debug.setmetatable(shape, scene_mt)                  -- a shape that claims to be a scene
    local ok, err = pcall(function() shape:add(torte.shape.sphere{}) end)
    assert(not ok and err:find("on a scene"), tostring(err))
    ok, err = pcall(torte.render, {scene = shape, camera = torte.camera.perspective{}, width = 2, height = 2})
    assert(not ok and err:find("must be a torte.scene, got torte.shape"), tostring(err))
    debug.setmetatable(scene, longs_mt)                  -- a scene that claims to be a long array
    ok, err = pcall(function() return #scene end)
    assert(not ok and err:find("expects a torte.data.longs, got torte.scene"), tostring(err))
    ok, err = pcall(torte.data.unpack_bits, scene, 4, 16)
    assert(not ok and err:find("torte.data.longs"), tostring(err))
    local f = io.tmpfile()                               -- a userdata of the io library
    debug.setmetatable(f, scene_mt)
    ok, err = pcall(function() f:add(torte.shape.sphere{}) end)
    assert(not ok and err:find("on a scene"), tostring(err))
    debug.setmetatable(longs, scene_mt)
    ok, err = pcall(function() longs:add(torte.shape.sphere{}) end)
    assert(not ok and err:find("on a scene"), tostring(err))
    scene, shape, f, longs = nil, nil, nil, nil
    collectgarbage()  -- every finalizer releases what its own userdata holds
    collectgarbage()
  )";
  const std::string err = s.run(script);
  INFO(err);
  CHECK(err.empty());
}

TEST_CASE("runtime: std::bad_alloc and torte::Interrupted in a binding become located Lua errors", "[runtime]") {
  RawState s;
  lua_pushcfunction(s.L, torte::lua::guarded<throws_bad_alloc>);
  lua_setglobal(s.L, "grow");
  lua_pushcfunction(s.L, torte::lua::guarded<throws_interrupted>);
  lua_setglobal(s.L, "stop");
  const std::string oom = s.run("local x = 1\ngrow()");
  CHECK_THAT(oom, Catch::StartsWith("[string"));
  CHECK_THAT(oom, Catch::Contains(":2: out of memory while running 'grow'"));
  CHECK_THAT(oom, Catch::Contains("--max-memory"));
  CHECK_THAT(oom, !Catch::Contains("std::bad_alloc"));
  CHECK_THAT(s.run("stop()"), Catch::Contains("interrupted while building the scene"));
}

TEST_CASE("runtime: precompiled chunks are refused everywhere, naming the file", "[runtime]") {
  LimitsDir dir("binary");
  // A chunk that would print if it ran, precompiled by a first run.
  const std::string make = dir.write("make.lua", R"(
    local f = assert(io.open("chunk.luac", "wb"))
    f:write(string.dump(function() print("ran") end))
    f:close()
  )");
  REQUIRE(run_in(dir, {"--quiet", make}).code == 0);
  SECTION("as the scene file") {
    const std::string line = check_error(run_in(dir, {"--quiet", dir / "chunk.luac"}));
    CHECK_THAT(line, Catch::Contains(dir / "chunk.luac"));
    CHECK_THAT(line, Catch::Contains("precompiled Lua chunks are not accepted"));
  }
  SECTION("through load, loadfile, dofile and require") {
    const std::string script = dir.write("load.lua", R"(
      local bytes = assert(io.open("chunk.luac", "rb")):read("a")
      local f, err = load(bytes, "chunk", "b")
      assert(f == nil and err == "load: precompiled Lua chunks are not accepted, only Lua source text", err)
      local pieces = {bytes:sub(1, 3), bytes:sub(4)}
      f, err = load(function() return table.remove(pieces, 1) end)
      assert(f == nil and err:find("precompiled"), err)
      f, err = loadfile("chunk.luac", "bt")
      assert(f == nil and err:find("chunk.luac: precompiled"), err)
      local ok
      ok, err = pcall(dofile, "chunk.luac")
      assert(not ok and err:find("chunk.luac: precompiled"), err)
      package.path = "./?.luac"
      ok, err = pcall(require, "chunk")
      assert(not ok and err:find("precompiled"), err)
      assert(load("return 1 + 1")() == 2, "source text still loads")
      error("all refused")
    )");
    const Result r = run_in(dir, {"--quiet", script});
    const std::string line = check_error(r);
    CHECK_THAT(line, Catch::Contains("all refused"));
    CHECK_THAT(r.out, !Catch::Contains("ran"));
  }
}

TEST_CASE("runtime: errors without a location get the script's file and line", "[runtime]") {
  LimitsDir dir("located");
  SECTION("C stack overflow in a scene:frame callback") {
    const std::string script = dir.write("frames.lua", "local s = torte.scene()\n"
                                                       "local function f(g) g:frame(f) end\n"
                                                       "f(s)\n");
    const std::string line = check_error(run_in(dir, {"--quiet", script}));
    CHECK_THAT(line, Catch::Contains("frames.lua:2: "));
    CHECK_THAT(line, Catch::Contains("stack overflow"));
  }
  SECTION("an error inside the embedded library") {
    const std::string script = dir.write("prelude.lua", "\n\nlocal opt = torte.options(42)\n");
    const std::string line = check_error(run_in(dir, {"--quiet", script}));
    CHECK_THAT(line, Catch::StartsWith("torte: error: " + script + ":3: [torte] torte.prelude:"));
  }
  SECTION("error values that are not strings") {
    CHECK_THAT(check_error(run_in(dir, {"--quiet", dir.write("nil.lua", "\nerror(nil)\n")})),
               Catch::Contains("nil.lua:2: (error object is a nil value)"));
    CHECK_THAT(check_error(run_in(dir, {"--quiet", dir.write("obj.lua", "error(torte.scene())\n")})),
               Catch::Contains("obj.lua:1: (error object is a torte.scene value)"));
    CHECK_THAT(check_error(run_in(dir, {"--quiet", dir.write("ts.lua", R"(
error(setmetatable({}, {__tostring = function() return "told" end}))
)")})),
               Catch::Contains("ts.lua:2: told"));
    CHECK_THAT(check_error(run_in(dir, {"--quiet", dir.write("tsf.lua", R"(
error(setmetatable({}, {__tostring = function() error("no") end}))
)")})),
               Catch::Contains("tsf.lua:2: (error object is a table value whose __tostring failed)"));
  }
  SECTION("require's multi-line message becomes one line") {
    const std::string line = check_error(run_in(dir, {"--quiet", dir.write("req.lua", "require 'no_such_module'\n")}));
    CHECK_THAT(line, Catch::Contains("req.lua:1: module 'no_such_module' not found: no field package.preload"));
  }
}

TEST_CASE("runtime: the Lua memory cap and the instruction budget end the script with one located line",
          "[runtime]") {
  LimitsDir dir("budgets");
  SECTION("a runaway table") {
    const std::string script = dir.write("grow.lua", "local t = {}\nfor i = 1, 1e12 do t[i] = {i} end\n");
    const std::string line = check_error(run_in(dir, {"--quiet", "--lua-memory", "32M", script}));
    CHECK_THAT(line, Catch::Contains("grow.lua:2: Lua memory limit of 32.0 MB reached"));
    CHECK_THAT(line, Catch::Contains("--lua-memory"));
  }
  SECTION("one huge string, caught and raised again") {
    const std::string script =
        dir.write("big.lua", "local ok, e = pcall(string.rep, 'x', 1 << 30)\nassert(not ok)\nerror(e)\n");
    const std::string line = check_error(run_in(dir, {"--quiet", "--lua-memory", "32M", script}));
    CHECK_THAT(line, Catch::Contains("big.lua:3: Lua memory limit of 32.0 MB reached"));
    CHECK_THAT(line, Catch::Contains("asked for 1.0 GB more"));
  }
  SECTION("an endless loop, also one that swallows the error with pcall") {
    const std::string script = dir.write("loop.lua", "\nwhile true do pcall(function() while true do end end) end\n");
    const std::string line = check_error(run_in(dir, {"--quiet", "--lua-instructions", "1000000", script}));
    CHECK_THAT(line, Catch::Contains("loop.lua:2: the script ran 1000000 Lua instructions, its limit"));
    CHECK_THAT(line, Catch::Contains("--lua-instructions N raises it"));
  }
  SECTION("the budget counts inside coroutines") {
    const std::string script = dir.write("co.lua", "coroutine.wrap(function()\n  while true do end\nend)()\n");
    const std::string line = check_error(run_in(dir, {"--quiet", "--sandbox", "--lua-instructions", "50000", script}));
    CHECK_THAT(line, Catch::Contains("co.lua:2: the script ran 50000 Lua instructions"));
  }
}

TEST_CASE("runtime: out-of-range option values are one line naming the option and the range", "[runtime][cli]") {
  LimitsDir dir("options");
  const std::string script = dir.write("ok.lua", "-- nothing\n");
  struct Case {
    std::vector<std::string> args;
    std::string expect;
  };
  const std::vector<Case> cases = {
      {{"--spp", "4294967297"}, "--spp expects an integer in [1, 2147483647], got '4294967297'"},
      {{"--spp", "4294967296"}, "--spp expects an integer in [1, 2147483647]"},
      {{"--spp", "3000000000"}, "--spp expects an integer in [1, 2147483647]"},
      {{"--spp", "-3"}, "--spp expects an integer in [1, 2147483647]"},
      {{"--threads", "4294967296"}, "--threads expects an integer in [1, 4096]"},
      {{"--threads", "0"}, "--threads expects an integer in [1, 4096]"},
      {{"--seed", "-1"}, "--seed expects an integer in [0, 9223372036854775807]"},
      {{"--seed", "18446744073709551616"}, "--seed expects an integer in [0, 9223372036854775807]"},
      {{"--seed", "1.5"}, "--seed expects an integer"},
      {{"--max-memory", "lots"}, "--max-memory: 'lots' is not a memory size"},
      {{"--max-memory", "10k"}, "--max-memory expects a size of at least 1.0 MB"},
      {{"--lua-memory", "-1G"}, "--lua-memory:"},
      {{"--lua-instructions", "1e9"}, "--lua-instructions expects an integer in [0, 9223372036854775807]"},
      {{"--allow-read", "/tmp"}, "--allow-read and --allow-write only apply with --sandbox"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = c.args;
    args.push_back(script);
    INFO(c.args[0] << " " << c.args[1]);
    const std::string line = check_error(run_in(dir, args));
    CHECK_THAT(line, Catch::Contains(c.expect));
    CHECK_THAT(line, Catch::EndsWith("(see 'torte --help')"));
  }
  SECTION("valid values run") {
    const Result r = run_in(dir, {"--max-memory", "2G", "--lua-memory", "64M", "--lua-instructions", "0",
                                  "--threads", "1", "--seed", "9223372036854775807", "--spp", "2147483647", script});
    check_no_crash(r);
    CHECK(r.code == 0);
    CHECK(r.err.empty());
  }
  SECTION("--help lists the new options") {
    const Result r = run_in(dir, {"--help"});
    for (const char* option : {"--max-memory", "--lua-memory", "--lua-instructions", "--sandbox", "--allow-read",
                               "--allow-write"})
      CHECK_THAT(r.out, Catch::Contains(option));
  }
}

namespace {

// Starts `script` (which writes "ready" on stdout when it reaches the code to interrupt), sends SIGINT and
// returns the result and the seconds from the signal to the exit.
Result interrupt(const TempDir& dir, const std::vector<std::string>& args, double* seconds, double wait = 0.3) {
  Process p(dir, args, dir.path.string());
  if (!p.wait_for_stdout("ready", 30)) FAIL("the script never became ready");
  std::this_thread::sleep_for(std::chrono::duration<double>(wait));
  p.send(SIGINT);
  const auto sent = std::chrono::steady_clock::now();
  Result r;
  if (!p.wait(30, &r)) FAIL("still running 30 s after SIGINT");
  *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  return r;
}

const char kReady[] = "io.stdout:write('ready\\n') io.stdout:flush()\n";

}  // namespace

TEST_CASE("runtime: the first Ctrl-C stops Lua code: exit 130 and one line, within a second", "[runtime][sigint]") {
  LimitsDir dir("sigint");
  struct Case {
    const char* name;
    std::string code;
    std::vector<std::string> flags;
  };
  const std::vector<Case> cases = {
      {"busy", "while true do end\n", {}},
      {"sandboxed", "while true do end\n", {"--sandbox"}},
      {"pcall", "while true do pcall(function() while true do end end) end\n", {}},
      {"coroutine", "coroutine.wrap(function() while true do end end)()\n", {}},
      {"resume", "local co = coroutine.create(function() while true do end end)\nassert(coroutine.resume(co))\n",
       {}},
      {"frame", "torte.scene():frame(function() while true do end end)\n", {}},
  };
  for (const Case& c : cases) {
    INFO("case " << c.name);
    const std::string script = dir.write(std::string(c.name) + ".lua", kReady + c.code);
    std::vector<std::string> args = c.flags;
    args.insert(args.end(), {"--quiet", script});
    double seconds = 0;
    const Result r = interrupt(dir, args, &seconds);
    check_no_crash(r);
    CHECK(r.code == 130);
    CHECK(seconds < 1);
    const std::vector<std::string> lines = lines_of(r.err);
    REQUIRE(lines.size() == 1);
    CHECK_THAT(lines[0], Catch::StartsWith("torte: interrupted while running the script (" + script + ":"));
  }
}

TEST_CASE("runtime: after Ctrl-C stops a render, the script saves it; a script that goes on is stopped later",
          "[runtime][sigint]") {
  LimitsDir dir("sigint_render");
  const std::string scene = R"(
local scene = torte.scene()
scene:add(torte.shape.sphere{radius = 1})
scene:add(torte.light.infinite{radiance = 1})
)" + std::string(kReady) + R"(local img = torte.render{scene = scene, camera = torte.camera.perspective{eye = {0, 0, -4}},
                         width = 64, height = 64, spp = 10000000}
assert(img.interrupted)
)";
  SECTION("the image is saved and the run ends with 130, without an error line") {
    const std::string script = dir.write("save.lua", scene + "torte.save(img, 'out/partial.exr')\n");
    double seconds = 0;
    const Result r = interrupt(dir, {"--quiet", "--sandbox", script}, &seconds);
    check_no_crash(r);
    INFO("stderr: " << r.err);
    CHECK(r.code == 130);
    CHECK(seconds < 3);
    CHECK_THAT(r.err, !Catch::Contains("torte: error"));
    CHECK(fs::exists(dir.path / "out/partial.exr"));
    CHECK(fs::exists(dir.path / "out/partial.png"));
  }
  SECTION("a script still running after the grace period is stopped") {
    const std::string script = dir.write("spin.lua", scene + "while true do end\n");
    double seconds = 0;
    const Result r = interrupt(dir, {"--quiet", script}, &seconds);
    check_no_crash(r);
    CHECK(r.code == 130);
    CHECK(seconds > torte::lua::kInterruptGrace.count() - 1);
    CHECK(seconds < torte::lua::kInterruptGrace.count() + 5);
    CHECK_THAT(r.err, Catch::Contains("torte: interrupted: the script was still running"));
  }
  SECTION("a second render is not started") {
    const std::string script = dir.write("again.lua", scene + "torte.render{scene = scene, camera = "
                                                              "torte.camera.perspective{}, width = 4, height = 4}\n");
    double seconds = 0;
    const Result r = interrupt(dir, {"--quiet", script}, &seconds);
    check_no_crash(r);
    CHECK(r.code == 130);
    CHECK_THAT(r.err, Catch::Contains("torte: interrupted: torte.render was not started"));
    CHECK_THAT(r.err, !Catch::Contains("torte: error"));
  }
}
