// Small helpers for the text files lrvd reads itself (point and weight files) and the messages
// that quote them.
#pragma once

#include <filesystem>
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

//! When `path` exists but is neither a regular file nor a folder (a device such as /dev/zero, a
//! pipe, a socket): why lrvd does not read it (such an input has no end, or blocks); else "".
//! (/dev/stdin is read when the shell redirects a file to it, which makes it a regular file.)
inline std::string special_file_problem(const std::string& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status) || std::filesystem::is_regular_file(status) ||
      std::filesystem::is_directory(status))
    return "";
  return "is not a regular file but a device, a pipe or a socket; lrvd reads its inputs from regular files";
}

}  // namespace lrvd
