#include "core/quiet_stderr.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <mutex>

namespace torte {

namespace {

std::mutex g_mutex;
int g_depth = 0;       // live QuietStderr objects
int g_saved_fd = -1;   // the real stderr while redirected

}  // namespace

QuietStderr::QuietStderr() {
  std::lock_guard lock(g_mutex);
  if (g_depth++ > 0) return;
  std::fflush(stderr);
  const int null_fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (null_fd < 0) return;  // nothing to redirect to: messages stay visible, which is harmless
  g_saved_fd = ::fcntl(2, F_DUPFD_CLOEXEC, 3);
  if (g_saved_fd >= 0) ::dup2(null_fd, 2);
  ::close(null_fd);
}

QuietStderr::~QuietStderr() {
  std::lock_guard lock(g_mutex);
  if (--g_depth > 0 || g_saved_fd < 0) return;
  std::fflush(stderr);
  ::dup2(g_saved_fd, 2);
  ::close(g_saved_fd);
  g_saved_fd = -1;
}

}  // namespace torte
