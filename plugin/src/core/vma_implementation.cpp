// The one translation unit that compiles VulkanMemoryAllocator for the plugin. Functions come from the host's
// vkGetInstanceProcAddr at run time (no static Vulkan prototypes); the symbols stay hidden inside libtressvk.
#define VMA_IMPLEMENTATION
#define VMA_STATIC_VULKAN_FUNCTIONS 0
#define VMA_DYNAMIC_VULKAN_FUNCTIONS 1
#include <volk.h>
#include <vk_mem_alloc.h>
