// The one error type torte throws for bad input; the message is a complete sentence for the user.
#pragma once
#include <stdexcept>
#include <string>

namespace torte {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace torte
