#include "sandbox.h"

#include <algorithm>
#include <system_error>

#include "core/error.h"
#include "core/read_guard.h"

namespace fs = std::filesystem;

namespace torte::lua {

namespace {

const char kPolicyKey = 0;  // its address keys the FilePolicy in the Lua registry

// Linux gives up after 40 symlinks (ELOOP); so do we, keeping the rest as written (the open then fails).
constexpr int kMaxSymlinks = 40;

// Whether `tree` is `p` or one of its ancestors, compared by components ("/a/b" is not above "/a/bc").
bool is_below(const fs::path& p, const fs::path& tree) {
  auto t = tree.begin(), q = p.begin();
  for (; t != tree.end(); ++t, ++q) {
    if (t->empty()) continue;  // a trailing separator
    if (q == p.end() || *q != *t) return false;
  }
  return true;
}

std::string join(const std::vector<fs::path>& paths) {
  std::string out;
  for (const fs::path& p : paths) out += (out.empty() ? "" : ", ") + p.string();
  return out;
}

}  // namespace

fs::path resolve_path(const fs::path& path) {
  std::error_code ec;
  fs::path absolute = path.is_absolute() ? path : fs::current_path(ec) / path;
  // Components still to walk, the next one last.
  std::vector<fs::path> todo;
  for (const fs::path& c : absolute.relative_path()) todo.push_back(c);
  std::reverse(todo.begin(), todo.end());
  fs::path out = absolute.root_path();
  bool exists = true;  // whether `out` exists: below a missing component nothing can be a symlink
  int links = 0;
  while (!todo.empty()) {
    const fs::path c = std::move(todo.back());
    todo.pop_back();
    if (c.empty() || c == ".") continue;
    if (c == "..") {
      out = out.parent_path();  // `out` holds no symlink, so this is the kernel's '..'
      continue;
    }
    fs::path next = out / c;
    if (exists) {
      const fs::file_status st = fs::symlink_status(next, ec);
      if (!ec && fs::is_symlink(st) && links < kMaxSymlinks) {
        ++links;
        const fs::path target = fs::read_symlink(next, ec);
        if (!ec) {
          if (target.is_absolute()) out = target.root_path();
          const fs::path relative = target.relative_path();
          std::vector<fs::path> parts(relative.begin(), relative.end());
          for (auto it = parts.rbegin(); it != parts.rend(); ++it) todo.push_back(*it);
          continue;
        }
      }
      if (ec || st.type() == fs::file_type::not_found) exists = false;
    }
    out = std::move(next);
  }
  return out;
}

FilePolicy::FilePolicy(const FilePolicySettings& settings) {
  read_trees_.push_back(resolve_path(settings.script).parent_path());
  for (const std::string& d : settings.allow_read) read_trees_.push_back(resolve_path(d));
  write_trees_.push_back(resolve_path("out"));
  for (const std::string& d : settings.allow_write) write_trees_.push_back(resolve_path(d));
  for (const std::string& f : settings.outputs) write_dirs_.push_back(resolve_path(f).parent_path());
}

bool FilePolicy::may_write(const fs::path& resolved) const {
  for (const fs::path& tree : write_trees_)
    if (is_below(resolved, tree)) return true;
  const fs::path dir = resolved.parent_path();
  return std::find(write_dirs_.begin(), write_dirs_.end(), dir) != write_dirs_.end();
}

bool FilePolicy::may_read(const fs::path& resolved) const {
  for (const fs::path& tree : read_trees_)
    if (is_below(resolved, tree)) return true;
  return may_write(resolved);  // what the script may write it may read back (lights.lua reads its own map)
}

std::string FilePolicy::where_reads() const {
  return "a sandboxed script reads below " + join(read_trees_) + " and where it may write";
}

std::string FilePolicy::where_writes() const {
  std::string s = "a sandboxed script writes below " + join(write_trees_);
  if (!write_dirs_.empty()) s += " and in " + join(write_dirs_) + " (output=)";
  return s;
}

namespace {

std::string denial(const std::string& path, const fs::path& resolved, const char* function, const char* verb) {
  std::string s = function && *function ? std::string(function) + ": " : "";
  s += "'" + path + "'";
  if (resolved.string() != path) s += " (" + resolved.string() + ")";
  return s + " may not be " + verb + " under --sandbox";
}

}  // namespace

void FilePolicy::check_read(const std::string& path, const char* function) const {
  const fs::path resolved = resolve_path(path);
  if (may_read(resolved)) return;
  std::error_code ec;
  if (fs::symlink_status(resolved, ec).type() == fs::file_type::not_found) return;
  throw Error(denial(path, resolved, function, "read") + " (" + where_reads() + "; --allow-read DIR adds a directory)");
}

void FilePolicy::check_write(const std::string& path, const char* function) const {
  const fs::path resolved = resolve_path(path);
  if (may_write(resolved)) return;
  throw Error(denial(path, resolved, function, "written") + " (" + where_writes() +
              "; --allow-write DIR adds a directory)");
}

namespace {
const FilePolicy* g_nested_policy = nullptr;
void nested_read_guard(const std::string& path) {
  if (g_nested_policy) g_nested_policy->check_read(path, "");
}
}  // namespace

void guard_nested_reads(const FilePolicy* policy) {
  g_nested_policy = policy;
  set_read_guard(policy ? nested_read_guard : nullptr);
}

void set_file_policy(lua_State* L, const FilePolicy* policy) {
  lua_pushlightuserdata(L, const_cast<FilePolicy*>(policy));
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kPolicyKey);
}

const FilePolicy* file_policy(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kPolicyKey);
  const auto* policy = lua_islightuserdata(L, -1) ? static_cast<const FilePolicy*>(lua_touserdata(L, -1)) : nullptr;
  lua_pop(L, 1);
  return policy;
}

}  // namespace torte::lua
