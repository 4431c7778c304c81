#include "core/memory_budget.h"

#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/error.h"

namespace torte {

namespace {

std::atomic<uint64_t> g_limit{0};  // 0: the default

uint64_t read_cgroup_limit() {
  std::ifstream in("/sys/fs/cgroup/memory.max");  // cgroup v2; "max" means none
  std::string s;
  if (in >> s && !s.empty() && std::isdigit(static_cast<unsigned char>(s[0]))) return std::stoull(s);
  return 0;
}

}  // namespace

uint64_t available_memory() {
  static const uint64_t bytes = [] {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    uint64_t phys = pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : (uint64_t(8) << 30);
    const uint64_t cg = read_cgroup_limit();
    if (cg > 0 && cg < phys) phys = cg;
    return phys;
  }();
  return bytes;
}

uint64_t memory_limit() {
  const uint64_t set = g_limit.load(std::memory_order_relaxed);
  return set ? set : available_memory() / 4 * 3;
}

void set_memory_limit(uint64_t bytes) { g_limit.store(bytes, std::memory_order_relaxed); }

uint64_t resident_memory() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  unsigned long long size = 0, resident = 0;
  const int n = std::fscanf(f, "%llu %llu", &size, &resident);
  std::fclose(f);
  return n == 2 ? uint64_t(resident) * uint64_t(sysconf(_SC_PAGESIZE)) : 0;
}

uint64_t peak_resident_memory() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  unsigned long long kb = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "VmHWM: %llu kB", &kb) == 1) break;
  std::fclose(f);
  return uint64_t(kb) * 1024;
}

void reserve_memory(uint64_t bytes, std::string_view what) {
  if (bytes < (uint64_t(16) << 20)) return;
  const uint64_t limit = memory_limit();
  const uint64_t held = resident_memory();
  if (bytes > limit || held + bytes > limit)
    throw Error(std::string(what) + " needs ~" + format_bytes(bytes) +
                (held > (uint64_t(64) << 20) ? " more (the process holds " + format_bytes(held) + ")" : "") +
                ", over the memory limit of " + format_bytes(limit) + " (set with --max-memory)");
}

uint64_t checked_bytes(uint64_t count, uint64_t size, std::string_view what) {
  uint64_t out;
  if (__builtin_mul_overflow(count, size, &out))
    throw Error(std::string(what) + " needs more than 2^64 bytes (" + std::to_string(count) + " x " +
                std::to_string(size) + ")");
  return out;
}

std::string format_bytes(uint64_t bytes) {
  const char* units[] = {"B", "KB", "MB", "GB", "TB", "PB", "EB"};
  double v = double(bytes);
  int u = 0;
  while (v >= 1024 && u < 6) v /= 1024, ++u;
  char buf[32];
  if (u == 0)
    std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(bytes));
  else
    std::snprintf(buf, sizeof buf, v < 100 ? "%.1f %s" : "%.0f %s", v, units[u]);
  return buf;
}

uint64_t parse_byte_size(std::string_view text) {
  const std::string s(text);
  auto bad = [&]() -> Error {
    return Error("'" + s + "' is not a memory size (expected e.g. 1.5GB, 800MB, 64k or a byte count)");
  };
  size_t i = 0;
  while (i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '.')) ++i;
  if (i == 0) throw bad();
  double v;
  try {
    size_t used = 0;
    v = std::stod(s.substr(0, i), &used);
    if (used != i) throw bad();
  } catch (const std::logic_error&) {
    throw bad();
  }
  while (i < s.size() && s[i] == ' ') ++i;
  std::string unit;
  for (; i < s.size(); ++i) unit += char(std::tolower(static_cast<unsigned char>(s[i])));
  if (!unit.empty() && unit.back() == 'b') unit.pop_back();
  if (!unit.empty() && unit.back() == 'i') unit.pop_back();  // "GiB"
  double scale;
  if (unit.empty()) scale = 1;
  else if (unit == "k") scale = 1024.0;
  else if (unit == "m") scale = 1024.0 * 1024;
  else if (unit == "g") scale = 1024.0 * 1024 * 1024;
  else if (unit == "t") scale = 1024.0 * 1024 * 1024 * 1024;
  else throw bad();
  const double bytes = v * scale;
  if (!std::isfinite(bytes) || bytes < 1 || bytes > 1.8e19) throw bad();
  return uint64_t(bytes);
}

}  // namespace torte
