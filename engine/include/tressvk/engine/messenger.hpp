// VK_EXT_debug_utils messenger that counts and prints every validation message.
//
// Counting rule: every WARNING or ERROR counts, except the Vulkan loader's own GENERAL messages (id name
// "Loader Message": drivers it could not load and the like), which are printed but say nothing about our use of
// the API. INFO and VERBOSE messages are not requested.
#pragma once

#include <volk.h>

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace tressvk::engine {

struct ValidationMessage {
  VkDebugUtilsMessageSeverityFlagBitsEXT severity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  VkDebugUtilsMessageTypeFlagsEXT types = 0;
  int32_t id_number = 0;
  std::string id_name;  // e.g. "SYNC-HAZARD-WRITE-AFTER-WRITE" or "VUID-..."
  std::string text;     // the full message
};

// Whether a message counts as a validation message (see the rule above).
bool counts_as_validation(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
                          const char* id_name);

// Formats a message for a log: "[validation error] VUID-...: text".
std::string format_message(const ValidationMessage& message);

// Receives the messenger's callbacks. Owned by the Device and kept alive until after vkDestroyInstance, so
// that messages emitted while the instance itself is created or destroyed are counted too.
class MessageLog {
 public:
  // Called for every counted message before it is stored. Return true to mark it handled (the message is still
  // counted, but not printed); the test fixture uses this to turn messages into test failures.
  using Hook = std::function<bool(const ValidationMessage&)>;

  void set_print(bool print) { print_ = print; }
  void set_hook(Hook hook);

  uint64_t count() const;          // counted (validation) messages so far
  uint64_t error_count() const;    // of those, ERROR severity
  std::vector<ValidationMessage> messages() const;  // the counted messages (the first 256 are kept)

  // The VkDebugUtilsMessengerCreateInfoEXT whose pUserData is this log. Also chained into VkInstanceCreateInfo.
  VkDebugUtilsMessengerCreateInfoEXT create_info();

  // Entry point for the messenger (and for unit tests, which feed it synthetic messages).
  void receive(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
               const VkDebugUtilsMessengerCallbackDataEXT* data);

 private:
  mutable std::mutex mutex_;
  Hook hook_;
  bool print_ = true;
  uint64_t count_ = 0;
  uint64_t errors_ = 0;
  std::vector<ValidationMessage> kept_;
};

}  // namespace tressvk::engine
