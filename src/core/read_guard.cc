#include "core/read_guard.h"

namespace torte {

namespace {
ReadGuard g_guard = nullptr;
}

void set_read_guard(ReadGuard guard) { g_guard = guard; }

void check_nested_read(const std::string& path) {
  if (g_guard) g_guard(path);
}

}  // namespace torte
