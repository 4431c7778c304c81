// How a render is run, beside what it computes (RenderSettings): checkpoints to write and one to resume from.
// None of it changes the image: a resumed render ends with the same pixels as one never stopped.
#pragma once
#include <string>

namespace torte {

struct RenderControl {
  std::string checkpoint;         // --checkpoint FILE: "" writes none
  double checkpoint_every = 60;   // --checkpoint-every: seconds between checkpoints (and one on Ctrl-C)
  std::string resume;             // --resume FILE: "" starts from a black film
  /// What the image depends on ("name=value;..."): settings and the scene's fingerprint. Checkpoints carry it
  /// and a resume refuses one whose key differs (film/checkpoint.h).
  std::string key;
};

}  // namespace torte
