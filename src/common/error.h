// Errors lrvd reports to its caller: InputError for anything a user passed that the algorithms
// cannot handle, WriteError for an output the system did not take whole (a full disk). The message
// is one line the user can act on, naming the first offending element or the file.
#pragma once

#include <stdexcept>
#include <string>

namespace lrvd {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

//! Writing an output failed after it was opened (a full disk, /dev/full, a file-size limit): not the
//! input's fault. The CLI exits 1 on it, not 2.
class WriteError : public std::runtime_error {
 public:
  explicit WriteError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace lrvd
