// Bring-up failures must say what is wrong. These need the Vulkan loader but create no device (each fails
// before vkCreateDevice), so they live in the CPU test executable and do not disturb the fixture's
// one-device-per-process rule.
#include <tressvk/engine/device.hpp>

#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <cstdlib>
#include <string>

using namespace tressvk::engine;
using Catch::Matchers::ContainsSubstring;

namespace {
// Sets an environment variable for one scope and restores the previous value.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (old_.empty()) ::unsetenv(name_);
    else ::setenv(name_, old_.c_str(), 1);
  }

 private:
  const char* name_;
  std::string old_;
};
}  // namespace

TEST_CASE("requesting validation without the layer installed fails with a clear message", "[engine]") {
  // VK_LAYER_PATH replaces the loader's layer search path, so the installed layer is not found.
  const ScopedEnv layers("VK_LAYER_PATH", "/nonexistent-tressvk-layer-dir");
  DeviceOptions options;
  options.validation = true;
  CHECK_THROWS_WITH(Device(options), ContainsSubstring("VK_LAYER_KHRONOS_validation") &&
                                         ContainsSubstring("vulkan-validationlayers"));
}

TEST_CASE("TRESSVK_DEVICE naming no device fails with a clear message", "[engine]") {
  const ScopedEnv device("TRESSVK_DEVICE", "no-such-gpu-xyz");
  CHECK_THROWS_WITH(Device(DeviceOptions{}), ContainsSubstring("no-such-gpu-xyz") &&
                                                 ContainsSubstring("TRESSVK_DEVICE"));
  const ScopedEnv index("TRESSVK_DEVICE", "99");
  CHECK_THROWS_WITH(Device(DeviceOptions{}), ContainsSubstring("out of range"));
}
