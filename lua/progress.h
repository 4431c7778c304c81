// Progress on stderr while rendering (or building a scene): a redrawn bar on a terminal, periodic plain lines
// otherwise.
#pragma once
#include <chrono>
#include <mutex>
#include <string>

#include "render/render.h"

namespace torte::lua {

class ConsoleProgress : public ProgressSink {
 public:
  // `rate_unit` names the rate shown: the "rays" argument of update() per second, in millions.
  explicit ConsoleProgress(std::string label, std::string rate_unit = "Mrays/s");
  void update(uint64_t samples_done, uint64_t samples_total, uint64_t rays, double elapsed) override;
  // Ends the bar line (on a terminal) after the render.
  void finish();

 private:
  std::string label_, rate_unit_;
  bool tty_;
  std::mutex mutex_;
  double last_print_ = -1;
  int last_percent_ = -1;
  bool printed_ = false;
};

// "1.2 s", "3 min 04 s", ...
std::string format_duration(double seconds);

}  // namespace torte::lua
