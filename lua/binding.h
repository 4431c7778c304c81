// Helpers shared by the Lua bindings: keyword-table checking, userdata that own C++ objects, and the guard that
// turns C++ exceptions into Lua errors with the script's file and line.
//
// We use Debian's C++ build of Lua (lua5.4-c++): lua_error unwinds with a C++ exception, so destructors of
// objects alive in a binding run when a Lua error passes through it.
#pragma once
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include <cstdint>
#include <memory>
#include <new>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/rgb.h"
#include "core/transform.h"

namespace torte::lua {

// How a binding body failed, for raise_binding_failure.
struct BindingFailure {
  enum Kind { kError, kOutOfMemory, kInterrupted } kind = kError;
  std::string message;
};
/// Raises the Lua error for `failure` at the caller's location: the message of a torte::Error, "out of memory
/// while running '<function>'" for std::bad_alloc, and for torte::Interrupted a message the runtime recognises
/// as the end of the run by Ctrl-C (exit code 130, no error line).
[[noreturn]] void raise_binding_failure(lua_State* L, const BindingFailure& failure);

// Runs a binding body; torte::Error and std::exception become a Lua error at the caller's location. Lua's own
// errors (a C++ exception of another type in lua5.4-c++) pass through untouched.
template <int (*Body)(lua_State*)>
int guarded(lua_State* L) {
  BindingFailure failure;
  try {
    return Body(L);
  } catch (const Interrupted& e) {
    failure = {BindingFailure::kInterrupted, e.what()};
  } catch (const std::bad_alloc&) {
    failure = {BindingFailure::kOutOfMemory, {}};
  } catch (const std::length_error& e) {  // a container asked for more than it can ever hold
    failure = {BindingFailure::kOutOfMemory, e.what()};
  } catch (const std::exception& e) {
    failure = {BindingFailure::kError, e.what()};
  }
  raise_binding_failure(L, failure);  // outside the handler: the C++ exception is gone before Lua's is thrown
}

// ---- userdata owning a std::shared_ptr<T>; T's metatable is named by LuaName<T>::value -----------------
// The type of a torte userdata is a tag inside its own bytes, not its metatable: debug.setmetatable (or a
// registry edit) can give a userdata any metatable, and a binding must never read one type's bytes as another's.
template <class T>
struct LuaName;
template <>
struct LuaName<Transform> {
  static constexpr const char* value = "torte.transform";
};

/// The first bytes of every full userdata torte creates. `magic` tells torte's userdata from the io library's
/// (or any other), `tag` is the address of TypeTag<T>::id, `release` destroys what it owns (may be null).
struct UserdataHeader {
  static constexpr uint64_t kMagic = 0x746f7274652e7564;  // "torte.ud"
  uint64_t magic;
  const void* tag;
  const char* name;  // for error messages, e.g. "torte.mesh"
  void (*release)(UserdataHeader*);
};
template <class T>
struct TypeTag {
  static constexpr char id = 0;  // only its address matters: one per type
};

/// The header of the userdata at idx if it is one of torte's and carries `tag` (any torte type when `tag` is
/// null), else nullptr. Checks the value's type and size before reading a byte of it.
UserdataHeader* tagged_userdata(lua_State* L, int idx, const void* tag);
/// Gives the userdata on the top of the stack the metatable named `header.name`, creating it (a __gc that calls
/// the header's release, __name, and a __metatable that hides it from getmetatable) on first use.
void set_tagged_metatable(lua_State* L, const UserdataHeader& header);
/// The __gc of every metatable torte makes (set_tagged_metatable's and hand-made ones such as torte.data.longs'):
/// releases what the userdata's own header says it holds, whatever metatable a script gave it.
int collect_tagged(lua_State* L);

template <class T>
struct Boxed {
  UserdataHeader header;
  std::shared_ptr<T> object;
};

template <class T>
void push_object(lua_State* L, std::shared_ptr<T> object) {
  const UserdataHeader header{UserdataHeader::kMagic, &TypeTag<T>::id, LuaName<T>::value,
                              [](UserdataHeader* h) { reinterpret_cast<Boxed<T>*>(h)->object.reset(); }};
  // Header and object are complete before anything else can fail, so a __gc never sees half an object.
  new (lua_newuserdatauv(L, sizeof(Boxed<T>), 0)) Boxed<T>{header, std::move(object)};
  set_tagged_metatable(L, header);
}

// The object at idx if it is a T, else nullptr.
template <class T>
std::shared_ptr<T> to_object(lua_State* L, int idx) {
  auto* b = reinterpret_cast<Boxed<T>*>(tagged_userdata(L, idx, &TypeTag<T>::id));
  return b ? b->object : nullptr;  // a collected (reset) object also comes back as nullptr
}

// Name of a Lua value's type for error messages (torte types by their own names).
std::string type_name(lua_State* L, int idx);

// ---- keyword arguments -----------------------------------------------------------------------------------
// Reads fields of the table at `index`; finish() rejects keys that were never read, so a typo is an error that
// names the key. Getters throw torte::Error("<function>: ...") and the guard adds the script location.
class KwArgs {
 public:
  KwArgs(lua_State* L, int index, std::string function);
  bool has(const char* key);
  double number(const char* key);
  double number(const char* key, double fallback);
  int integer(const char* key, int fallback);
  bool boolean(const char* key, bool fallback);
  std::string string(const char* key);
  std::string string(const char* key, const std::string& fallback);
  Vec3f vec3(const char* key);
  Vec3f vec3(const char* key, Vec3f fallback);
  // A colour: {r, g, b} or one number for grey.
  Rgb rgb(const char* key, Rgb fallback);
  Transform transform(const char* key);  // identity when absent
  std::vector<double> numbers(const char* key);  // a flat array; nested {x,y,z} entries are flattened
  // A torte object of type T; required unless `optional`.
  template <class T>
  std::shared_ptr<T> object(const char* key, bool optional = false);
  // Pushes the raw value of key (nil when absent) and marks it read.
  void push(const char* key);
  // Throws if the table holds keys that were not read.
  void finish();
  [[noreturn]] void fail(const char* key, const std::string& problem) const;
  const std::string& function() const { return function_; }
  lua_State* state() const { return L_; }

 private:
  bool fetch(const char* key);  // pushes the value; returns false (and pops) when nil
  lua_State* L_;
  int index_;
  std::string function_;
  std::set<std::string> read_;
};

template <class T>
std::shared_ptr<T> KwArgs::object(const char* key, bool optional) {
  if (!fetch(key)) {
    if (optional) return nullptr;
    fail(key, std::string("is required (a ") + LuaName<T>::value + ")");
  }
  std::shared_ptr<T> p = to_object<T>(L_, -1);
  if (!p) {
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    fail(key, std::string("must be a ") + LuaName<T>::value + ", got " + got);
  }
  lua_pop(L_, 1);
  return p;
}

// Reads a Vec3 from {x, y, z} at idx; throws with `what` in the message.
Vec3f check_vec3(lua_State* L, int idx, const std::string& what);

// Registers functions into the table at the top of the stack.
void set_functions(lua_State* L, const luaL_Reg* functions);

// ---- methods of types whose __index is a function (fields computed on access) -----------------------------
// Their methods live in the metatable's `__methods` table, so one list serves lookup and the API reference's
// check (tests/io/test_lua_api_doc.cc enumerates `__methods` and table `__index`es).
/// Sets `__methods` of the metatable at the top of the stack to a table of `methods`.
void set_methods(lua_State* L, const luaL_Reg* methods);
/// Pushes method `key` of the torte userdata at idx, looked up in its type's own registered metatable (not the
/// one a script may have given the value); returns false, pushing nothing, when the type has no such method.
bool push_method(lua_State* L, int idx, const std::string& key);

/// Called by KwArgs::finish with the function's name and every key it read, before unknown keys are rejected;
/// the API reference's test records which keys each function accepts. Null (no observer) unless a test sets one.
using KeyObserver = void (*)(const std::string& function, const std::set<std::string>& keys);
void set_key_observer(KeyObserver observer);
// Ensures torte.<name> exists as a table and leaves it on the stack (torte table must be at `torte_index`).
void push_subtable(lua_State* L, int torte_index, const char* name);

}  // namespace torte::lua
