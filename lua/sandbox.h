// The file policy of --sandbox: a sandboxed script reads only below its own directory, below --allow-read
// directories and where it may write; it writes only below ./out and --allow-write directories and in the
// directory of each output= argument of the command line. Paths are resolved as the kernel would (symlinks,
// also a dangling last one, '.' and '..') before the check. docs/security.md explains the rule.
#pragma once
#include <lua.h>

#include <filesystem>
#include <string>
#include <vector>

namespace torte::lua {

struct FilePolicySettings {
  std::string script;                    // the scene file: its directory is readable
  std::vector<std::string> allow_read;   // --allow-read DIR: readable, with everything below
  std::vector<std::string> allow_write;  // --allow-write DIR: writable (and readable), with everything below
  std::vector<std::string> outputs;      // output=FILE arguments: FILE's directory is writable (not below it)
};

class FilePolicy {
 public:
  /// Resolves every directory now, relative to the working directory; ./out is always writable.
  explicit FilePolicy(const FilePolicySettings& settings);
  /// Throws torte::Error("<function>: reading '<path>' is not allowed by --sandbox (...)") unless the resolved
  /// path may be read. A path that does not exist passes (there is nothing to read; the open then fails).
  void check_read(const std::string& path, const char* function) const;
  /// The same for creating or overwriting `path`.
  void check_write(const std::string& path, const char* function) const;
  bool may_read(const std::filesystem::path& resolved) const;
  bool may_write(const std::filesystem::path& resolved) const;

 private:
  std::string where_reads() const;
  std::string where_writes() const;
  std::vector<std::filesystem::path> read_trees_;   // readable with everything below
  std::vector<std::filesystem::path> write_trees_;  // writable with everything below
  std::vector<std::filesystem::path> write_dirs_;   // files directly in them are writable
};

/// `path` as the kernel resolves it: absolute (against the working directory), every symlink followed (a
/// dangling one to its target), '.' and '..' applied after the symlinks before them; the part that does not
/// exist is appended as written.
std::filesystem::path resolve_path(const std::filesystem::path& path);

/// Makes `policy` (it must outlive L; nullptr: no policy) the one check_read and check_write apply for L.
void set_file_policy(lua_State* L, const FilePolicy* policy);
/// The policy of L, or nullptr when every path is allowed (no --sandbox).
const FilePolicy* file_policy(lua_State* L);
/// Applies `policy` also to the files that readers open because another file names them (an OBJ's mtllib;
/// core/read_guard.h), for the whole process; nullptr removes it.
void guard_nested_reads(const FilePolicy* policy);

}  // namespace torte::lua
