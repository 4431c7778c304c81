// Shared helpers for the tests in tests/io/: a per-process temp directory, and running the built torte binary
// (TORTE_BINARY) with stdout and stderr captured to files, a timeout, and checks for one-line errors.
#pragma once

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace torte::test {

// A fresh directory per test case and process (ctest may run test cases in parallel), removed afterwards:
// <temp>/torte_<suite>_<pid>_<name>.
struct TempDir {
  std::filesystem::path path;
  TempDir(const std::string& suite, const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("torte_" + suite + "_" + std::to_string(getpid()) + "_" + name)) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string operator/(const std::string& file) const { return (path / file).string(); }
  // Writes a file (a script, a mesh, ...) into the directory and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = *this / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
};

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Whether heavy tests run at reduced sizes: TORTE_TEST_REDUCED set and not "0", as the sanitizer builds' ctest
// environment does (tests/sanitizers/README.md).
inline bool reduced_test_sizes() {
  const char* v = std::getenv("TORTE_TEST_REDUCED");
  return v != nullptr && *v != '\0' && std::string(v) != "0";
}

struct Result {
  bool exited = false;  // exited normally (not killed by a signal)
  int code = -1;        // exit code when `exited`, -1 otherwise
  int signal = 0;       // the terminating signal otherwise
  std::string out, err;
};

// A started torte process whose stdout and stderr go to files in `dir`, running in `cwd` (empty: the test's
// working directory).
class Process {
 public:
  Process(const TempDir& dir, const std::vector<std::string>& args, const std::string& cwd = {})
      : out_path_(dir / "stdout.txt"), err_path_(dir / "stderr.txt") {
    std::vector<std::string> argv_s{TORTE_BINARY};
    argv_s.insert(argv_s.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, out_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    // The child runs in `cwd` (glibc >= 2.29 has this action).
    if (!cwd.empty()) posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
    const int rc = posix_spawn(&pid_, TORTE_BINARY, &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) {
      pid_ = -1;
      FAIL("cannot start " << TORTE_BINARY << ": " << std::strerror(rc));
    }
  }
  ~Process() {
    if (pid_ > 0) {  // still running after a failed check or a timeout: do not leave it behind
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;
  std::string stdout_text() const { return read_file(out_path_); }
  void send(int sig) { kill(pid_, sig); }
  // Waits up to `timeout` seconds; returns false (process still running) on timeout.
  bool wait(double timeout, Result* r) {
    const auto start = std::chrono::steady_clock::now();
    for (;;) {
      int status = 0;
      const pid_t w = waitpid(pid_, &status, WNOHANG);
      if (w == pid_) {
        pid_ = -1;
        r->exited = WIFEXITED(status);
        r->code = r->exited ? WEXITSTATUS(status) : -1;
        r->signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
        r->out = read_file(out_path_);
        r->err = read_file(err_path_);
        return true;
      }
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  // Waits up to `timeout` seconds for `text` to appear on stdout; returns whether it did.
  bool wait_for_stdout(const std::string& text, double timeout) const {
    const auto start = std::chrono::steady_clock::now();
    while (stdout_text().find(text) == std::string::npos &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < timeout)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    return stdout_text().find(text) != std::string::npos;
  }

 private:
  std::string out_path_, err_path_;
  pid_t pid_ = -1;
};

// Runs torte with `args` to the end (in `cwd`, see Process); fails the test case if it takes over `timeout` s.
inline Result run_torte(const TempDir& dir, const std::vector<std::string>& args, double timeout,
                        const std::string& cwd = {}) {
  Process p(dir, args, cwd);
  Result r;
  if (!p.wait(timeout, &r)) FAIL("torte did not finish within " << timeout << " s");
  return r;
}

// No crash: a normal exit, and nothing on stderr that a crash or an uncaught exception would print.
inline void check_no_crash(const Result& r) {
  INFO("stderr: " << r.err);
  CHECK(r.exited);
  CHECK(r.signal == 0);
  CHECK_THAT(r.err, !Catch::Contains("terminate called"));
  CHECK_THAT(r.err, !Catch::Contains("Segmentation"));
  CHECK_THAT(r.err, !Catch::Contains("Aborted"));
  CHECK_THAT(r.err, !Catch::Contains("stack traceback"));
}

// A failed run: exit code 1 and exactly one line on stderr, starting "torte: error:". Returns that line.
inline std::string check_error(const Result& r) {
  check_no_crash(r);
  INFO("stderr: " << r.err);
  CHECK(r.code == 1);
  const std::vector<std::string> lines = lines_of(r.err);
  REQUIRE(lines.size() == 1);
  CHECK_THAT(lines[0], Catch::StartsWith("torte: error: "));
  CHECK(r.err.back() == '\n');
  return lines[0];
}

}  // namespace torte::test
