// Errors lrvd reports to its caller: InputError for anything a user passed that the algorithms
// cannot handle. Its message is one line the user can act on, naming the first offending element.
#pragma once

#include <stdexcept>
#include <string>

namespace lrvd {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace lrvd
