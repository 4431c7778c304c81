// Runs a fuzz harness's entry point on files, without libFuzzer: `fuzz_<name>_replay [--skip-missing]
// FILE_OR_DIR...` feeds every file (directories: every file inside, recursively, in sorted order) once;
// --skip-missing passes over paths that do not exist (a harness without regressions yet). A crash or a sanitizer report ends
// the process, and an input running longer than TORTE_REPLAY_TIMEOUT seconds (default 90: inputs take well under a second
// alone, but a loaded 2-core machine running ASan builds beside has stretched one past 20 s) aborts it with the
// file's name, so ctest names the input that regressed. An input that raises the process's peak RSS past
// TORTE_REPLAY_MAX_RSS_MB (default 1536, as libFuzzer's -rss_limit_mb would) fails the replay with its name: the
// replay has no malloc limit, and an allocation the promises forbid (a 2 GB buffer for a 2 KB file) may still pass
// without a crash. Outside sanitizer builds one allocation through operator new (the C++ libraries' buffers:
// OpenEXR's, OpenImageIO's) larger than TORTE_REPLAY_MAX_ALLOC_MB (default 1024) aborts with the input's name, as
// libFuzzer's -malloc_limit_mb would: a buffer that is never touched raises no RSS.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <cstring>
#include <vector>

#include "harness.h"

namespace {

char g_current[4096];

void on_alarm(int) {
  const char prefix[] = "fuzz replay: timed out on ";
  (void)!write(2, prefix, sizeof prefix - 1);
  (void)!write(2, g_current, strnlen(g_current, sizeof g_current));
  (void)!write(2, "\n", 1);
  std::abort();
}

long peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024;  // kilobytes on Linux
}

size_t g_max_alloc = 0;  // 0 until main has read the limit (static initialisers allocate freely)
int g_stderr = 2;

}  // namespace

// Sanitizer runtimes define operator new themselves (GCC 12 has no __has_feature, only the __SANITIZE_ macros).
#ifndef __has_feature
#define __has_feature(x) 0
#endif
#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__) && !__has_feature(address_sanitizer) && \
    !__has_feature(thread_sanitizer)
void* operator new(size_t n) {
  if (g_max_alloc && n > g_max_alloc) {
    // To the stderr main saw: harnesses silence fd 2 around library calls (core/quiet_stderr.h).
    dprintf(g_stderr, "fuzz replay: %s allocated %zu bytes at once (limit %zu MB, TORTE_REPLAY_MAX_ALLOC_MB)\n",
            g_current, n, g_max_alloc >> 20);
    std::abort();
  }
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }
#endif

int main(int argc, char** argv) {
  // Paths are resolved first: harnesses may change the working directory when they initialise.
  std::vector<std::string> files;
  bool skip_missing = false;
  for (int i = 1; i < argc; ++i) {
    std::error_code ec;
    if (std::string_view(argv[i]) == "--skip-missing") {
      skip_missing = true;
    } else if (std::filesystem::is_directory(argv[i], ec)) {
      for (const auto& e : std::filesystem::recursive_directory_iterator(argv[i]))
        if (e.is_regular_file()) files.push_back(std::filesystem::absolute(e.path()).string());
    } else if (std::filesystem::is_regular_file(argv[i], ec)) {
      files.push_back(std::filesystem::absolute(argv[i]).string());
    } else if (!skip_missing) {
      std::fprintf(stderr, "fuzz replay: %s: no such file or directory\n", argv[i]);
      return 2;
    }
  }
  std::sort(files.begin(), files.end());
  LLVMFuzzerInitialize(&argc, &argv);
  const char* t = std::getenv("TORTE_REPLAY_TIMEOUT");
  const unsigned timeout = t ? unsigned(std::atoi(t)) : 90;
  const char* m = std::getenv("TORTE_REPLAY_MAX_RSS_MB");
  const long max_rss_mb = m ? std::atol(m) : 1536;
  const char* a = std::getenv("TORTE_REPLAY_MAX_ALLOC_MB");
  g_max_alloc = size_t(a ? std::atol(a) : 1024) << 20;
  g_stderr = dup(2);
  std::signal(SIGALRM, on_alarm);
  for (const std::string& f : files) {
    std::ifstream in(f, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    snprintf(g_current, sizeof g_current, "%s", f.c_str());
    alarm(timeout);
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
    alarm(0);
    if (const long rss = peak_rss_mb(); rss > max_rss_mb) {
      std::fprintf(stderr, "fuzz replay: %s raised the peak RSS to %ld MB (limit %ld MB, TORTE_REPLAY_MAX_RSS_MB)\n",
                   f.c_str(), rss, max_rss_mb);
      return 1;
    }
  }
  std::printf("fuzz replay: %zu inputs ran without a crash\n", files.size());
  return 0;
}
