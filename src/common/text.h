// Small helpers for the text files lrvd reads itself (point and weight files) and the messages
// that quote them.
#pragma once

#include <string>

namespace lrvd {

//! Drops a UTF-8 byte-order mark from the start of a file's first line (some editors write one).
inline void skip_byte_order_mark(std::string& first_line) {
  if (first_line.compare(0, 3, "\xEF\xBB\xBF") == 0) first_line.erase(0, 3);
}

//! A token quoted in a message: NUL bytes as \x00, which would otherwise end the message where an
//! exception's what() is read (the command line escapes the other control bytes).
inline std::string shown(const std::string& token) {
  std::string out;
  for (char c : token) {
    if (c == '\0')
      out += "\\x00";
    else
      out += c;
  }
  return out;
}

}  // namespace lrvd
