// Sanitizer settings of tressvk_plugin_sanitize_tests (see leak_check.hpp): leaks are checked inside the test
// cases, not at exit; allocations of the Vulkan loader, the validation layer and Mesa (process-lifetime caches,
// not TressVK's) are not reported.
extern "C" const char* __asan_default_options() { return "leak_check_at_exit=0"; }
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libvulkan.so\nleak:libVkLayer_khronos_validation.so\nleak:libvulkan_lvp.so\nleak:libLLVM\n";
}
