// A process-wide check for files that other files name (an OBJ's mtllib): readers call check_nested_read before
// opening one, and the Lua sandbox installs a guard that applies its file policy (lua/sandbox.h). Files a script
// names itself are checked by the bindings (lua/file_access.h); this covers what the readers open on their own.
#pragma once
#include <string>

namespace torte {

/// Throws torte::Error when reading `path` is not allowed; nullptr: everything is.
using ReadGuard = void (*)(const std::string& path);

/// Installs `guard` for the whole process (nullptr removes it). Not thread-safe: set it before any reading starts.
void set_read_guard(ReadGuard guard);
/// Calls the installed guard, if any.
void check_nested_read(const std::string& path);

}  // namespace torte
