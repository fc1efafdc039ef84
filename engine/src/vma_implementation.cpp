// The one translation unit that compiles VulkanMemoryAllocator for the engine. No static Vulkan prototypes:
// VMA fetches its functions through volk's vkGetInstanceProcAddr / vkGetDeviceProcAddr (see device.cpp).
#define VMA_IMPLEMENTATION
#define VMA_STATIC_VULKAN_FUNCTIONS 0
#define VMA_DYNAMIC_VULKAN_FUNCTIONS 1
#include <volk.h>
#include <vk_mem_alloc.h>
