// Not a test suite of its own: a program that must FAIL. Its one test case leaks a VkBuffer, so the validation
// layer reports the leak when the fixture destroys the device after the last test; the fixture must then make
// the process exit non-zero and name the message (see the add_test in CMakeLists.txt).
#include <tressvk/test/vulkan.hpp>

#include <catch2/catch_test_macros.hpp>

TEST_CASE("leaks a buffer on purpose", "[vulkan][engine]") {
  const VkDevice device = tressvk::test::device().device();
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = 256;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer leaked = VK_NULL_HANDLE;
  REQUIRE(vkCreateBuffer(device, &info, nullptr, &leaked) == VK_SUCCESS);
  CHECK(leaked != VK_NULL_HANDLE);
}
