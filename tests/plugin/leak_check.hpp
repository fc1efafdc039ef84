// Host-memory leak checks inside a test case, for the ASan build (tressvk_plugin_sanitize_tests). LeakSanitizer's
// usual check at exit runs after the Vulkan loader has unloaded the layer and the driver, whose caches then show
// up as unattributable leaks; checking while they are loaded gives named stacks and a failure in the test case
// that leaked. Without ASan this is a no-op.
#pragma once

#include <catch2/catch_test_macros.hpp>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#define TVK_TEST_HAS_LSAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#include <sanitizer/lsan_interface.h>
#define TVK_TEST_HAS_LSAN 1
#endif
#endif

namespace tressvk::test {

inline void check_no_host_leaks() {
#if defined(TVK_TEST_HAS_LSAN)
  INFO("LeakSanitizer found unreachable host memory (report printed above)");
  CHECK(__lsan_do_recoverable_leak_check() == 0);
#endif
}

}  // namespace tressvk::test
