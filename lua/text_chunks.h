// Lua chunks from source text only. Lua's loader of precompiled (binary) chunks trusts its input, and a crafted
// chunk crashes the interpreter, so the scene file, load, loadfile, dofile and require's Lua-file searcher all
// load with mode "t" and refuse binary chunks with a message naming the file.
#pragma once
#include <lua.h>

namespace torte::lua {

/// Loads the Lua source file `path` and pushes it as a function (returns LUA_OK), or pushes a one-line message
/// naming the file (a precompiled chunk: "<path>: precompiled Lua chunks are not accepted ...") and returns the
/// error status.
int load_text_file(lua_State* L, const char* path);

/// Replaces load, loadfile, dofile and the Lua-file searcher of require (package.searchers[2]) by versions that
/// load text only and, for files, ask check_read first (lua/file_access.h). Needs the base and package
/// libraries open.
void install_text_loaders(lua_State* L);

}  // namespace torte::lua
