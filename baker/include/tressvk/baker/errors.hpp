// Errors the baker reports. The CLI maps them to exit codes: InputError -> 2, IoError -> 3.
#pragma once

#include <stdexcept>
#include <string>

namespace tressvk::baker {

// The input is invalid. what() names the file and the line (text) or field/byte offset (binary).
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A file could not be opened, read or written.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace tressvk::baker
