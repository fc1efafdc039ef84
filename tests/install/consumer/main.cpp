// Links the installed libtressvk from C++: version check, device requirements and a refused context creation
// (a null create-info must give TVK_ERROR_INVALID_ARGUMENT, not a crash or an exception).
#include <tressvk/tressvk.h>

#include <cstdio>

int main() {
  if (TVK_CHECK_VERSION() != TVK_SUCCESS) {
    std::fprintf(stderr, "consumer (C++): header/library version mismatch (library %u)\n", tressvk_version());
    return 1;
  }
  TvkDeviceRequirements req{};
  tressvk_get_device_requirements(&req);
  if (req.min_api_version < VK_API_VERSION_1_3) {
    std::fprintf(stderr, "consumer (C++): unexpected minimum Vulkan version\n");
    return 1;
  }
  TvkContext context = nullptr;
  const TvkResult r = tressvk_create_context(nullptr, &context);
  if (r != TVK_ERROR_INVALID_ARGUMENT || context != nullptr) {
    std::fprintf(stderr, "consumer (C++): tressvk_create_context(NULL) returned %s\n", tressvk_result_string(r));
    return 1;
  }
  std::printf("consumer (C++): TressVK %u linked; invalid arguments refused (%s)\n", tressvk_version(),
              tressvk_result_string(r));
  return 0;
}
