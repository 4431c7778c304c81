// docs/lua-api.md against the bindings, so the reference cannot drift: every torte function and method has a
// section, every section names something that exists, every example runs, and every `Keys of` table lists
// exactly the keys its function reads (recorded through lua::set_key_observer while the examples run). The
// LuaLS stubs in lua/types/torte.lua are generated from the same sections; TORTE_UPDATE_LUA_STUBS=1 (make
// lua-stubs) rewrites them.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>

#include "binding.h"
#include "runtime.h"
#include "types.h"
#include "lua_api_doc.h"
#include "test_support.h"

namespace torte {
namespace {

using test::ApiSection;

const std::string kDoc = std::string(TORTE_SOURCE_DIR) + "/docs/lua-api.md";
const std::string kStubs = std::string(TORTE_SOURCE_DIR) + "/lua/types/torte.lua";

std::vector<ApiSection> doc_sections() {
  std::ifstream in(kDoc);
  REQUIRE(in.good());
  std::stringstream s;
  s << in.rdbuf();
  return test::parse_api_doc(s.str());
}

// What the torte module defines: its functions and values by dotted name, and the methods of its userdata types
// as "<short type>:<method>" (the short type is the last part of the metatable's name: torte.voxel.grid -> grid).
struct ApiNames {
  std::set<std::string> functions, values;
  std::map<std::string, std::string> types;  // short type -> metatable name
};

void walk_table(lua_State* L, const std::string& prefix, ApiNames& names, std::set<const void*>& seen) {
  if (!seen.insert(lua_topointer(L, -1)).second) return;
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING) {
      const std::string name = prefix + "." + lua_tostring(L, -2);
      if (lua_isfunction(L, -1)) names.functions.insert(name);
      else names.values.insert(name);
      if (lua_istable(L, -1)) walk_table(L, name, names, seen);
    }
    lua_pop(L, 1);
  }
}

ApiNames api_names() {
  lua_State* L = luaL_newstate();
  luaL_openlibs(L);
  lua::RunContext ctx;
  ctx.quiet = true;
  lua::set_run_context(L, &ctx);
  lua::open_torte_module(L, lua::RunOptions{});
  // The prelude adds torte.options and torte.save; transforms make their metatable on first use.
  REQUIRE(luaL_dostring(L, "require 'torte.prelude'; local _ = torte.translate(0, 0, 0)") == LUA_OK);
  ApiNames names;
  std::set<const void*> seen;
  lua_getglobal(L, "torte");
  walk_table(L, "torte", names, seen);
  lua_pop(L, 1);
  lua_pushnil(L);
  while (lua_next(L, LUA_REGISTRYINDEX) != 0) {
    const bool torte_table = lua_type(L, -2) == LUA_TSTRING && lua_istable(L, -1) &&
                             std::string(lua_tostring(L, -2)).rfind("torte.", 0) == 0;
    if (torte_table && lua_getfield(L, -1, "__name") == LUA_TSTRING) {  // a metatable of a torte type
      const std::string meta = lua_tostring(L, -1);
      const std::string type = meta.substr(meta.rfind('.') + 1);
      names.types[type] = meta;
      for (const char* field : {"__index", "__methods"}) {
        if (lua_getfield(L, -2, field) == LUA_TTABLE) {
          lua_pushnil(L);
          while (lua_next(L, -2) != 0) {
            if (lua_type(L, -2) == LUA_TSTRING && lua_isfunction(L, -1))
              names.functions.insert(type + ":" + lua_tostring(L, -2));
            lua_pop(L, 1);
          }
        }
        lua_pop(L, 1);
      }
    }
    if (torte_table) lua_pop(L, 1);  // __name
    lua_pop(L, 1);
  }
  lua_close(L);
  return names;
}

std::mutex recorded_mutex;
std::map<std::string, std::set<std::string>> recorded;  // KwArgs name -> every key it read in any example

void record_keys(const std::string& function, const std::set<std::string>& keys) {
  std::lock_guard<std::mutex> lock(recorded_mutex);
  recorded[function].insert(keys.begin(), keys.end());
}

std::string join(const std::set<std::string>& s) {
  std::string out;
  for (const std::string& x : s) out += (out.empty() ? "" : ", ") + x;
  return out;
}

TEST_CASE("lua api doc: every function and method has a section, and every section names one", "[lua_api]") {
  const std::vector<ApiSection> sections = doc_sections();
  const ApiNames names = api_names();
  std::set<std::string> documented, duplicated, unknown, without_example;
  for (const ApiSection& s : sections) {
    if (!documented.insert(s.name).second) duplicated.insert(s.name);
    const bool function = names.functions.count(s.name) > 0;
    if (!function && !names.values.count(s.name)) unknown.insert(s.name);
    if (function && s.examples.empty()) without_example.insert(s.name);
  }
  std::set<std::string> missing;
  for (const std::string& f : names.functions)
    if (!documented.count(f)) missing.insert(f);
  INFO("undocumented: " << join(missing));
  CHECK(missing.empty());
  INFO("sections naming nothing the module defines: " << join(unknown));
  CHECK(unknown.empty());
  INFO("documented twice: " << join(duplicated));
  CHECK(duplicated.empty());
  INFO("functions without an example: " << join(without_example));
  CHECK(without_example.empty());
  CHECK(sections.size() > 100);
}

TEST_CASE("lua api doc: every example runs, and the key tables are the keys each function reads", "[lua_api]") {
  const std::vector<ApiSection> sections = doc_sections();
  test::TempDir dir("lua_api", "examples");
  const auto cwd = std::filesystem::current_path();
  lua::set_key_observer(record_keys);
  std::vector<std::string> failures;
  int ran = 0;
  for (const ApiSection& s : sections)
    for (const test::ApiExample& e : s.examples) {
      if (!e.run) continue;
      const auto here = dir.path / ("example_" + std::to_string(e.line));
      std::filesystem::create_directories(here);
      std::ofstream(here / "example.lua") << e.code;
      std::filesystem::current_path(here);
      lua::RunOptions options;
      options.script = (here / "example.lua").string();
      options.quiet = true;
      const int code = lua::run_script(options);
      std::filesystem::current_path(cwd);
      ++ran;
      if (code != lua::kExitOk)
        failures.push_back("lua-api.md:" + std::to_string(e.line) + " (" + s.name + ") exited with " +
                           std::to_string(code) + " (its error is on stderr above)");
    }
  lua::set_key_observer(nullptr);
  std::string failed;
  for (const std::string& f : failures) failed += "\n  " + f;
  INFO(ran << " examples ran; failed:" << failed);
  CHECK(failures.empty());
  CHECK(ran > 100);

  std::map<std::string, std::set<std::string>> tables;
  std::set<std::string> twice;
  for (const ApiSection& s : sections)
    for (const test::ApiKeyTable& t : s.tables) {
      if (tables.count(t.function)) twice.insert(t.function);
      for (const test::ApiKey& k : t.keys) tables[t.function].insert(k.key);
    }
  INFO("key tables given twice: " << join(twice));
  CHECK(twice.empty());
  for (const auto& [function, keys] : recorded) {
    if (keys.empty()) continue;  // takes an (empty) table but no keys: nothing to document
    INFO(function << " read keys in the examples");
    REQUIRE(tables.count(function));
    std::set<std::string> undocumented;
    std::set_difference(keys.begin(), keys.end(), tables[function].begin(), tables[function].end(),
                        std::inserter(undocumented, undocumented.end()));
    INFO(function << " reads keys its table does not list: " << join(undocumented));
    CHECK(undocumented.empty());
  }
  for (const auto& [function, keys] : tables) {
    INFO("Keys of `" << function << "`: no example called it (or it never checks its keys)");
    REQUIRE(recorded.count(function));
    std::set<std::string> unread;
    std::set_difference(keys.begin(), keys.end(), recorded[function].begin(), recorded[function].end(),
                        std::inserter(unread, unread.end()));
    INFO(function << " lists keys no example made it read: " << join(unread));
    CHECK(unread.empty());
  }
}

// ---- LuaLS stubs ---------------------------------------------------------------------------------------------

// A LuaLS type for the type words of the key tables; anything else is `any`.
std::string lua_type(const std::string& word) {
  static const std::map<std::string, std::string> types = {
      {"number", "number"},
      {"integer", "integer"},
      {"boolean", "boolean"},
      {"string", "string"},
      {"colour", "number|number[]"},
      {"vec3", "number[]"},
      {"texture", "torte.texture"},
      {"colour or texture", "number|number[]|torte.texture"},
      {"number or texture", "number|torte.texture"},
      {"transform", "torte.transform"},
      {"material", "torte.material"},
      {"shape", "torte.shape"},
      {"light", "torte.light"},
      {"camera", "torte.camera"},
      {"scene", "torte.scene"},
      {"group", "torte.scene"},
      {"mesh", "torte.mesh"},
      {"image", "torte.image"},
      {"filter", "torte.filter"},
      {"instance", "torte.instance"},
      {"table", "table"},
      {"array of number", "number[]"},
      {"array of string", "string[]"},
      {"function", "function"},
  };
  const auto it = types.find(word);
  return it == types.end() ? "any" : it->second;
}

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

// The parameters of a signature "f(a, b [, c])" or "f{...}" as names; a table argument is `args`.
std::vector<std::string> parameters(const std::string& signature) {
  const size_t open = signature.find_first_of("({");
  if (open == std::string::npos) return {};
  if (signature[open] == '{') return {"args"};
  const size_t close = signature.find(')', open);
  std::vector<std::string> out;
  std::string word;
  for (size_t i = open + 1; i < close && i < signature.size(); ++i) {
    const char c = signature[i];
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
      word += c;
    } else if (c == '.' && signature.compare(i, 3, "...") == 0) {
      out.push_back("...");
      i += 2;
    } else if (c == '{') {  // an inline keyword table among positional arguments
      if (word.empty()) out.push_back("args");
      while (i < close && signature[i] != '}') ++i;
    } else if (c == '=') {  // "name = default": skip to the next comma
      if (!word.empty()) out.push_back(word);
      word.clear();
      while (i + 1 < close && signature[i + 1] != ',') ++i;
    } else if (!word.empty()) {
      out.push_back(word);
      word.clear();
    }
  }
  if (!word.empty()) out.push_back(word);
  static const std::set<std::string> keywords = {"and", "break", "do", "else", "elseif", "end", "false", "for",
                                                  "function", "goto", "if", "in", "local", "nil", "not", "or",
                                                  "repeat", "return", "then", "true", "until", "while"};
  for (std::string& p : out)
    if (keywords.count(p)) p += "_";  // a parameter documented as `function` is `function_` in Lua
  std::vector<std::string> unique;
  for (const std::string& p : out)
    if (std::find(unique.begin(), unique.end(), p) == unique.end()) unique.push_back(p);
  return unique;
}

std::string class_name(const std::string& function) {
  std::string c = function;
  std::replace(c.begin(), c.end(), ':', '.');
  std::replace(c.begin(), c.end(), ' ', '_');
  return c + ".args";
}

std::string generate_stubs(const std::vector<ApiSection>& sections, const ApiNames& names) {
  std::ostringstream out;
  out << "---@meta torte\n"
      << "-- Generated from docs/lua-api.md by tests/io/test_lua_api_doc.cc (make lua-stubs); do not edit.\n"
      << "-- Editors with the Lua language server (LuaLS) complete and check scene scripts with these stubs\n"
      << "-- (.luarc.json at the repository's root points at this directory).\n\n";
  // Classes of the userdata types and the module tables, declared before the functions that use them.
  std::set<std::string> classes;
  for (const auto& [type, meta] : names.types) classes.insert(meta);
  auto local_name = [](std::string meta) {  // torte.voxel.grid -> torte_voxel_grid, the methods' receiver
    std::replace(meta.begin(), meta.end(), '.', '_');
    return meta;
  };
  for (const std::string& meta : classes) out << "---@class " << meta << "\nlocal " << local_name(meta) << " = {}\n";
  out << "\n---@class torte\ntorte = {}\n";
  std::set<std::string> tables;
  for (const std::string& v : names.values) {
    bool is_table = false;
    for (const std::string& f : names.functions)
      if (f.rfind(v + ".", 0) == 0) is_table = true;
    if (is_table) tables.insert(v);
  }
  for (const std::string& t : tables) out << t << " = {}\n";
  out << "\n";
  for (const ApiSection& s : sections) {
    const bool method = s.name.find(':') != std::string::npos;
    const bool function = names.functions.count(s.name) > 0;
    if (!s.contract.empty()) out << "---" << one_line(s.contract) << "\n";
    if (!function) {
      if (!tables.count(s.name) && !s.signature.empty()) out << "---`" << s.signature << "`\n";
      if (!tables.count(s.name)) out << s.name << " = nil\n\n";
      continue;
    }
    std::string args_class;
    for (const test::ApiKeyTable& t : s.tables) {
      args_class = class_name(t.function);
      break;
    }
    for (const std::string& p : parameters(s.signature)) {
      if (p == "...") {
        out << "---@param ... any\n";
      } else if (p == "args" && !args_class.empty()) {
        out << "---@param args " << args_class << "\n";
      } else {
        out << "---@param " << p << " any\n";
      }
    }
    const size_t arrow = s.signature.find("->");
    if (arrow != std::string::npos) {
      std::string ret = s.signature.substr(arrow + 2);
      ret = ret.substr(ret.find_first_not_of(' '));
      out << "---@return " << (ret.rfind("torte.", 0) == 0 ? ret.substr(0, ret.find_first_of(" ,")) : lua_type(ret))
          << "\n";
    }
    std::string target = s.name;
    if (method) {
      const std::string type = s.name.substr(0, s.name.find(':'));
      const auto it = names.types.find(type);
      target = local_name(it == names.types.end() ? type : it->second) + s.name.substr(s.name.find(':'));
    }
    std::string params;
    for (const std::string& p : parameters(s.signature)) params += (params.empty() ? "" : ", ") + p;
    out << "function " << target << "(" << params << ") end\n\n";
  }
  for (const ApiSection& s : sections)
    for (const test::ApiKeyTable& t : s.tables) {
      out << "---@class " << class_name(t.function) << "\n";
      for (const test::ApiKey& k : t.keys)
        out << "---@field " << k.key << (k.fallback == "required" ? " " : "? ") << lua_type(k.type) << " "
            << one_line(k.description) << (k.fallback == "required" || k.fallback == "-" ? "" : " (default " + k.fallback + ")")
            << "\n";
      out << "\n";
    }
  out << "return torte\n";  // what `require "torte"` gives, for the language server
  return out.str();
}

TEST_CASE("lua api doc: lua/types/torte.lua is what the reference generates", "[lua_api][lua_api_stubs]") {
  const std::string stubs = generate_stubs(doc_sections(), api_names());
  if (const char* update = std::getenv("TORTE_UPDATE_LUA_STUBS"); update && std::string(update) == "1") {
    std::filesystem::create_directories(std::filesystem::path(kStubs).parent_path());
    std::ofstream(kStubs, std::ios::binary) << stubs;
  }
  INFO("regenerate with `make lua-stubs` after changing docs/lua-api.md");
  CHECK(test::read_file(kStubs) == stubs);
  // The stubs are Lua that loads (LuaLS reads them as code; a bad signature line would break every completion).
  lua_State* L = luaL_newstate();
  const int status = luaL_loadbuffer(L, stubs.data(), stubs.size(), "=torte.lua");
  INFO((status == LUA_OK ? "" : lua_tostring(L, -1)));
  CHECK(status == LUA_OK);
  lua_close(L);
}

}  // namespace
}  // namespace torte
