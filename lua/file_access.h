// The seam through which every binding that opens a file a script names asks whether the run allows it: all
// paths are allowed by default, and under --sandbox reads only below the script's directory and --allow-read
// directories, writes only to the output paths the command line allows (docs/security.md).
#pragma once
#include <lua.h>

#include <string>

namespace torte::lua {

/// Throws torte::Error("<function>: reading '<path>' is not allowed ...") when the run's policy forbids
/// reading `path`. Call before opening any file (or listing any directory) whose name came from a script.
void check_read(lua_State* L, const std::string& path, const char* function);
/// The same for creating or overwriting `path`.
void check_write(lua_State* L, const std::string& path, const char* function);

}  // namespace torte::lua
