// saagen reports every user-facing problem as one line: where, what, and what to do.
#pragma once

#include <stdexcept>
#include <string>

namespace saagen {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace saagen
