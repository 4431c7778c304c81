// Decoding fuzz bytes into Lua values for the harnesses that drive the torte bindings: numbers including NaN,
// infinities, huge and boundary values (as floats or integers), strings (torte's own keywords and names, or raw
// bytes), tables (vectors, arrays, keyword tables with torte's keys), torte objects, Lua functions and odd values
// (tables whose metamethods raise, cycles, other userdata types).
//
// Values that size work (width, height, spp, levels, ...) are either small or absurd, never merely large: a
// large legitimate render only makes the fuzzer time out, while an absurd one must be refused with an error.
// Only an image side may be huge (46341, 1e5, ...): cheap beside a small other side, refused beside a huge one.
#pragma once
#include <lua.h>

#include <string>
#include <string_view>
#include <vector>

#include "fuzz_input.h"
#include "fuzz_support.h"

namespace torte::fuzz {

/// Every keyword any torte binding reads (a fuzzed table whose other keys were accepted is a broken promise).
const std::vector<std::string>& torte_keywords();
/// Strings worth passing as values: enumerations, metal names, the fixture files, odd paths.
const std::vector<std::string>& torte_words();
/// True for keys whose value sizes the work (render sizes, sample counts, subdivision levels, ...).
bool sizes_work(std::string_view key);

/// The registry tables the value maker uses: constructors of one object of each torte type, Lua functions and odd
/// values. Install once per state (after torte.prelude), with the fixture files present in the scratch directory.
void install_value_pools(FuzzLua& lua);
/// Writes the small fixture files the pools and generated strings refer to (fx.ply, fx.obj, fx.mtl, fx.png, fx.exr,
/// a directory fx.dir) into the current directory.
void write_fixtures();
/// Removes everything in the current directory but the fixtures (files a sequence wrote).
void remove_non_fixtures();

class LuaValueMaker {
 public:
  /// `slots`: absolute stack index of a table of earlier results (0: none).
  LuaValueMaker(lua_State* L, FuzzInput& in, int slots = 0) : L_(L), in_(in), slots_(slots) {}

  void push_value(int depth = 0, std::string_view key = {});
  void push_number(std::string_view key = {});
  void push_string();
  /// A table of key = value pairs, mostly torte keywords; sometimes a positional entry or a non-string key.
  /// Sets `only_known_keys` to whether every key is a string from torte_keywords().
  void push_kwargs(int depth, bool* only_known_keys = nullptr);
  void push_object();    // one torte object of a fuzzed type (a fresh one, or from the slots)
  void push_function();  // a Lua function from the pool (callbacks for scene:frame, ...)

 private:
  void push_pool_entry(const char* pool, size_t index);
  lua_State* L_;
  FuzzInput& in_;
  int slots_;
};

/// "{k = v, ...}" (sorted, one level) or tostring(v), for TORTE_FUZZ_VERBOSE output.
std::string describe(lua_State* L, int index);

/// Number of entries in a pool (see install_value_pools): "objects", "functions", "odd".
size_t pool_size(lua_State* L, const char* pool);

}  // namespace torte::fuzz
