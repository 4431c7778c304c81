// Keeps a library's own stderr lines (libpng's "libpng error: ..." while OpenImageIO reads a broken PNG) out of the
// one-line errors torte promises: the library's message reaches the user through the library's error string.
#pragma once

namespace torte {

/// Points file descriptor 2 at /dev/null for the object's lifetime (nested and concurrent uses share one
/// redirection). For short library calls on the scene-building thread: any thread's stderr output meanwhile is
/// lost, so never hold one across a render or a progress display.
class QuietStderr {
 public:
  QuietStderr();
  ~QuietStderr();
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;
};

}  // namespace torte
