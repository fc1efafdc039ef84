// Bounds-checked reading of little-endian binary files (.tfx, .tfxbone): every failure names the file, the field
// and the byte offset.
#pragma once

#include <tressvk/baker/errors.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>

namespace tressvk::baker {

template <typename T>
inline T load(std::span<const std::byte> b, uint64_t off) {
  T v{};
  std::memcpy(&v, b.data() + off, sizeof(T));
  return v;
}

inline std::string stem_of(std::string_view name) {
  std::string_view s = name;
  if (auto slash = s.find_last_of("/\\"); slash != std::string_view::npos) s = s.substr(slash + 1);
  if (auto dot = s.find_last_of('.'); dot != std::string_view::npos && dot > 0) s = s.substr(0, dot);
  return std::string(s);
}

class BinaryCursor {
 public:
  BinaryCursor(std::span<const std::byte> b, std::string_view name) : b_(b), name_(name) {}
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(std::string(name_) + ": " + what + " (byte offset " + std::to_string(pos_) + ")");
  }
  template <typename T>
  T get(const char* field) {
    if (b_.size() - pos_ < sizeof(T)) fail(std::string("file ends inside field ") + field);
    T v = load<T>(b_, pos_);
    pos_ += sizeof(T);
    return v;
  }
  size_t remaining() const { return b_.size() - pos_; }
  size_t pos() const { return pos_; }
  void skip(size_t n) { pos_ += n; }

 private:
  std::span<const std::byte> b_;
  std::string_view name_;
  size_t pos_ = 0;
};

}  // namespace tressvk::baker
