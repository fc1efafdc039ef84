// tressvk.h first, then vulkan.h, as a host without volk writes it: the vk* prototypes must still be declared
// (an earlier tressvk.h defined VK_NO_PROTOTYPES and silently removed them). Compiling this file is the test.
#include <tressvk/tressvk.h>
#include <vulkan/vulkan.h>

#include <cstdio>
#include <type_traits>

#ifdef VK_NO_PROTOTYPES
#error "tressvk.h defined VK_NO_PROTOTYPES for the host"
#endif

static_assert(std::is_same_v<decltype(&vkCreateInstance), PFN_vkCreateInstance>,
              "vkCreateInstance must be declared after including tressvk.h");
static_assert(std::is_same_v<decltype(&vkCmdDispatch), PFN_vkCmdDispatch>);

int main() {
  std::printf("tressvk.h kept the vk* prototypes (TVK_VERSION_NUM %d)\n", TVK_VERSION_NUM);
  return 0;
}
