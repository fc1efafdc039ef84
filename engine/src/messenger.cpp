#include <tressvk/engine/messenger.hpp>

#include <cstdio>
#include <cstring>

namespace tressvk::engine {

namespace {

constexpr size_t kKeptMessages = 256;  // enough to report; a runaway loop must not eat memory

VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT types,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  static_cast<MessageLog*>(user)->receive(severity, types, data);
  return VK_FALSE;  // never abort the call: the counter decides what fails
}

const char* severity_name(VkDebugUtilsMessageSeverityFlagBitsEXT severity) {
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) return "error";
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return "warning";
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT) return "info";
  return "verbose";
}

}  // namespace

bool counts_as_validation(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
                          const char* id_name) {
  const bool serious = (severity & (VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                    VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)) != 0;
  const bool specific = (types & (VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                  VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT)) != 0;
  const bool from_loader = !specific && id_name && std::strcmp(id_name, "Loader Message") == 0;
  return serious && !from_loader;
}

std::string format_message(const ValidationMessage& message) {
  std::string out = "[";
  out += (message.types & VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT)    ? "validation "
         : (message.types & VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT) ? "performance "
                                                                              : "vulkan ";
  out += severity_name(message.severity);
  out += "] ";
  if (!message.id_name.empty()) {
    out += message.id_name;
    out += ": ";
  }
  out += message.text;
  return out;
}

void MessageLog::set_hook(Hook hook) {
  std::lock_guard lock(mutex_);
  hook_ = std::move(hook);
}

uint64_t MessageLog::count() const {
  std::lock_guard lock(mutex_);
  return count_;
}

uint64_t MessageLog::error_count() const {
  std::lock_guard lock(mutex_);
  return errors_;
}

std::vector<ValidationMessage> MessageLog::messages() const {
  std::lock_guard lock(mutex_);
  return kept_;
}

VkDebugUtilsMessengerCreateInfoEXT MessageLog::create_info() {
  VkDebugUtilsMessengerCreateInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = debug_callback;
  info.pUserData = this;
  return info;
}

void MessageLog::receive(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
                         const VkDebugUtilsMessengerCallbackDataEXT* data) {
  ValidationMessage message;
  message.severity = severity;
  message.types = types;
  if (data) {
    message.id_number = data->messageIdNumber;
    if (data->pMessageIdName) message.id_name = data->pMessageIdName;
    if (data->pMessage) message.text = data->pMessage;
  }
  if (!counts_as_validation(severity, types, data ? data->pMessageIdName : nullptr)) {
    if (print_ && (severity & (VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)))
      std::fprintf(stderr, "%s\n", format_message(message).c_str());
    return;
  }
  Hook hook;
  bool print = false;
  {
    std::lock_guard lock(mutex_);
    ++count_;
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ++errors_;
    if (kept_.size() < kKeptMessages) kept_.push_back(message);
    hook = hook_;
    print = print_;
  }
  // The hook runs outside the lock: it may call back into count() or messages().
  const bool handled = hook && hook(message);
  if (print && !handled) std::fprintf(stderr, "%s\n", format_message(message).c_str());
}

}  // namespace tressvk::engine
