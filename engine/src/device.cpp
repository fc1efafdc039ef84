#include <tressvk/engine/device.hpp>
#include <tressvk/engine/sync.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace tressvk::engine {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr uint32_t kMinApi = VK_API_VERSION_1_3;

void init_loader() {
  // volkInitialize is idempotent in effect: it reloads the same loader.
  if (volkInitialize() != VK_SUCCESS)
    throw Error("cannot load the Vulkan loader (libvulkan.so.1); install libvulkan1 (Debian) and a driver");
}

// Vulkan's two-call enumeration: `enumerate(&count, nullptr)`, then `enumerate(&count, data)`.
template <typename T, typename Enumerate>
std::vector<T> enumerate_all(Enumerate enumerate, const char* what) {
  uint32_t n = 0;
  vk_check(enumerate(&n, nullptr), what);
  std::vector<T> out(n);
  vk_check(enumerate(&n, out.data()), what);
  out.resize(n);
  return out;
}

std::vector<VkExtensionProperties> instance_extensions(const char* layer) {
  return enumerate_all<VkExtensionProperties>(
      [&](uint32_t* n, VkExtensionProperties* p) { return vkEnumerateInstanceExtensionProperties(layer, n, p); },
      "vkEnumerateInstanceExtensionProperties");
}

bool has_extension(const std::vector<VkExtensionProperties>& list, const char* name) {
  return std::any_of(list.begin(), list.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

bool has_layer(const char* name) {
  const auto layers = enumerate_all<VkLayerProperties>(
      [](uint32_t* n, VkLayerProperties* p) { return vkEnumerateInstanceLayerProperties(n, p); },
      "vkEnumerateInstanceLayerProperties");
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  return enumerate_all<VkPhysicalDevice>(
      [&](uint32_t* n, VkPhysicalDevice* p) { return vkEnumeratePhysicalDevices(instance, n, p); },
      "vkEnumeratePhysicalDevices");
}

std::vector<DeviceCandidate> describe(const std::vector<VkPhysicalDevice>& devices) {
  std::vector<DeviceCandidate> out;
  for (VkPhysicalDevice pd : devices) {
    VkPhysicalDeviceProperties p{};
    vkGetPhysicalDeviceProperties(pd, &p);
    out.push_back({p.deviceName, p.deviceType, p.apiVersion});
  }
  return out;
}

// A bare instance for enumeration; Vulkan 1.3 if the loader has it, else 1.0 so old loaders still list devices.
VkInstance create_bare_instance() {
  uint32_t loader_version = VK_API_VERSION_1_0;
  if (vkEnumerateInstanceVersion) vkEnumerateInstanceVersion(&loader_version);
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "tressvk-list";
  app.apiVersion = loader_version >= kMinApi ? kMinApi : VK_API_VERSION_1_0;
  VkInstanceCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  ci.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  vk_check(vkCreateInstance(&ci, nullptr, &instance), "vkCreateInstance");
  volkLoadInstanceOnly(instance);
  return instance;
}

std::string driver_text(VkPhysicalDevice pd, uint32_t api) {
  if (api < VK_API_VERSION_1_2) return {};
  VkPhysicalDeviceDriverProperties driver{};
  driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
  VkPhysicalDeviceProperties2 p2{};
  p2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
  p2.pNext = &driver;
  vkGetPhysicalDeviceProperties2(pd, &p2);
  std::string text = driver.driverName;
  if (driver.driverInfo[0]) text += std::string(" ") + driver.driverInfo;
  return text;
}

}  // namespace

std::string api_version_string(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

std::vector<DeviceInfo> list_devices() {
  init_loader();
  VkInstance instance = create_bare_instance();
  std::vector<DeviceInfo> out;
  try {
    const auto devices = physical_devices(instance);
    for (uint32_t i = 0; i < devices.size(); ++i) {
      VkPhysicalDeviceProperties p{};
      vkGetPhysicalDeviceProperties(devices[i], &p);
      out.push_back({i, p.deviceName, p.deviceType, p.apiVersion, driver_text(devices[i], p.apiVersion)});
    }
  } catch (...) {
    vkDestroyInstance(instance, nullptr);
    throw;
  }
  vkDestroyInstance(instance, nullptr);
  return out;
}

Device::Device(const DeviceOptions& options)
    : log_(std::make_shared<MessageLog>()), requirements_(options.requirements) {
  log_->set_print(options.print_messages);
  try {
    create_instance(options);
    if (options.create_surface) {
      surface_ = options.create_surface(instance_);
      if (surface_ == VK_NULL_HANDLE) throw Error("the window system could not create a Vulkan surface for the window");
    }
    pick_physical_device(options);
    create_device();
    create_allocator();
  } catch (...) {
    release();  // a throwing constructor runs no destructor: free what was created, then rethrow
    throw;
  }
}

Device::~Device() { release(); }

void Device::release() {
  if (device_) vkDeviceWaitIdle(device_);
  if (command_pool_) vkDestroyCommandPool(device_, command_pool_, nullptr);
  if (allocator_) vmaDestroyAllocator(allocator_);
  if (device_) vkDestroyDevice(device_, nullptr);
  if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
  if (messenger_) vkDestroyDebugUtilsMessengerEXT(instance_, messenger_, nullptr);
  if (instance_) vkDestroyInstance(instance_, nullptr);
  command_pool_ = VK_NULL_HANDLE;
  allocator_ = VK_NULL_HANDLE;
  device_ = VK_NULL_HANDLE;
  messenger_ = VK_NULL_HANDLE;
  surface_ = VK_NULL_HANDLE;
  instance_ = VK_NULL_HANDLE;
}

void Device::create_instance(const DeviceOptions& options) {
  init_loader();
  uint32_t loader_version = VK_API_VERSION_1_0;
  if (vkEnumerateInstanceVersion) vkEnumerateInstanceVersion(&loader_version);
  if (loader_version < kMinApi)
    throw Error("the Vulkan loader supports Vulkan " + api_version_string(loader_version) +
                "; TressVK needs Vulkan 1.3 (update libvulkan1)");

  sync_validation_ = options.sync_validation;
  validation_ = options.validation || options.sync_validation;

  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  const auto available = instance_extensions(nullptr);
  if (validation_) {
    if (!has_layer(kValidationLayer))
      throw Error(std::string("validation was requested but the layer ") + kValidationLayer +
                  " is not installed (Debian: apt-get install vulkan-validationlayers)");
    layers.push_back(kValidationLayer);
    const auto layer_extensions = instance_extensions(kValidationLayer);
    if (!has_extension(available, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) &&
        !has_extension(layer_extensions, VK_EXT_DEBUG_UTILS_EXTENSION_NAME))
      throw Error("validation was requested but VK_EXT_debug_utils is not available to count its messages");
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    debug_utils_ = true;
    if (sync_validation_) {
      // VVL 1.3.239 has no VK_EXT_layer_settings; VkValidationFeaturesEXT is the programmatic switch.
      if (!has_extension(layer_extensions, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME))
        throw Error(std::string("synchronization validation was requested but ") + kValidationLayer +
                    " does not offer VK_EXT_validation_features");
      extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    }
  } else if (has_extension(available, VK_EXT_DEBUG_UTILS_EXTENSION_NAME)) {
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);  // object names for debuggers and captures
    debug_utils_ = true;
  }

  for (const std::string& e : options.instance_extensions) {
    if (!has_extension(available, e.c_str()))
      throw Error("the window system needs the instance extension " + e + ", which the Vulkan loader does not offer");
    extensions.push_back(e.c_str());
  }

  VkApplicationInfo app{};

  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = options.app_name.c_str();
  app.pEngineName = "tressvk-engine";
  app.apiVersion = api_version_;

  VkDebugUtilsMessengerCreateInfoEXT messenger_info = log_->create_info();
  const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{};
  features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;

  VkInstanceCreateInfo ci{};

  ci.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  ci.pApplicationInfo = &app;
  ci.enabledLayerCount = static_cast<uint32_t>(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  ci.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  // The chained messenger also reports problems inside vkCreateInstance / vkDestroyInstance.
  if (validation_) {
    ci.pNext = &messenger_info;
    if (sync_validation_) messenger_info.pNext = &features;
  }
  vk_check(vkCreateInstance(&ci, nullptr, &instance_), "vkCreateInstance");
  volkLoadInstance(instance_);
  if (debug_utils_) {
    VkDebugUtilsMessengerCreateInfoEXT info = log_->create_info();
    vk_check(vkCreateDebugUtilsMessengerEXT(instance_, &info, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }
}

bool env_flag(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && v[0] != '\0' && v[0] != '0';
}

bool pipeline_stats_requested() { return env_flag("TRESSVK_PIPELINE_STATS"); }

void Device::pick_physical_device(const DeviceOptions& options) {
  const auto devices = physical_devices(instance_);
  const auto candidates = describe(devices);
  std::string selector = options.device;
  if (selector.empty())
    if (const char* env = std::getenv("TRESSVK_DEVICE")) selector = env;
  const DeviceChoice choice = choose_device(candidates, selector, kMinApi);
  if (!choice.index)
    throw Error(choice.error + (options.device.empty() && !selector.empty() ? " (from TRESSVK_DEVICE)" : ""));
  physical_device_ = devices[*choice.index];
  vkGetPhysicalDeviceProperties(physical_device_, &properties_);
}

void Device::create_device() {
  // The plugin's requirements are merged in before vkCreateDevice, as any host engine must do.
  const DeviceRequirements& req = requirements_;
  api_version_ = std::max(api_version_, req.min_api_version);
  if (properties_.apiVersion < req.min_api_version)
    throw Error(std::string("device '") + name() + "' supports Vulkan " + api_version_string(properties_.apiVersion) +
                "; TressVK needs " + api_version_string(req.min_api_version));

  VkPhysicalDeviceVulkan13Features have13{};

  have13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  VkPhysicalDeviceVulkan12Features have12{};
  have12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  have12.pNext = &have13;
  VkPhysicalDeviceFeatures2 have{};
  have.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  have.pNext = &have12;
  vkGetPhysicalDeviceFeatures2(physical_device_, &have);

  std::string missing;
  auto need = [&](VkBool32 wanted, VkBool32 present, const char* what) {
    if (wanted && !present) missing += missing.empty() ? what : std::string(", ") + what;
  };
  need(VK_TRUE, have13.synchronization2, "synchronization2");
  need(VK_TRUE, have13.dynamicRendering, "dynamicRendering");
  // The engine's depth barriers use DEPTH_ATTACHMENT_OPTIMAL / DEPTH_READ_ONLY_OPTIMAL on depth-only images.
  need(VK_TRUE, have12.separateDepthStencilLayouts, "separateDepthStencilLayouts");
  need(req.synchronization2 ? VK_TRUE : VK_FALSE, have13.synchronization2, "synchronization2 (plugin)");
  need(req.dynamic_rendering ? VK_TRUE : VK_FALSE, have13.dynamicRendering, "dynamicRendering (plugin)");

  uint32_t n_ext = 0;
  vk_check(vkEnumerateDeviceExtensionProperties(physical_device_, nullptr, &n_ext, nullptr),
           "vkEnumerateDeviceExtensionProperties");
  std::vector<VkExtensionProperties> device_ext(n_ext);
  vk_check(vkEnumerateDeviceExtensionProperties(physical_device_, nullptr, &n_ext, device_ext.data()),
           "vkEnumerateDeviceExtensionProperties");
  std::vector<const char*> extensions;
  for (const std::string& e : req.extensions) {
    if (!has_extension(device_ext, e.c_str())) missing += missing.empty() ? e : ", " + e;
    extensions.push_back(e.c_str());
  }
  if (surface_ != VK_NULL_HANDLE) {
    if (!has_extension(device_ext, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
      missing += missing.empty() ? VK_KHR_SWAPCHAIN_EXTENSION_NAME : ", " VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  }
  if (!missing.empty())
    throw Error(std::string("device '") + name() + "' lacks what TressVK needs: " + missing);
  // TRESSVK_PIPELINE_STATS=1: the plugin reports its simulation pipelines' compiler statistics (registers, spills)
  // where the driver offers them.
  bool pipeline_stats =
      pipeline_stats_requested() && has_extension(device_ext, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
  if (pipeline_stats) {
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR have_stats{};
    have_stats.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR;
    VkPhysicalDeviceFeatures2 query{};
    query.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    query.pNext = &have_stats;
    vkGetPhysicalDeviceFeatures2(physical_device_, &query);
    pipeline_stats = have_stats.pipelineExecutableInfo == VK_TRUE;
  }
  if (pipeline_stats) extensions.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);

  // Queue: the first family that does graphics and compute (graphics implies transfer).
  uint32_t n_fam = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &n_fam, nullptr);
  std::vector<VkQueueFamilyProperties> families(n_fam);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &n_fam, families.data());
  bool found = false;
  for (uint32_t i = 0; i < n_fam && !found; ++i) {
    const VkQueueFlags f = families[i].queueFlags;
    VkBool32 present = VK_TRUE;
    if (surface_ != VK_NULL_HANDLE)
      vk_check(vkGetPhysicalDeviceSurfaceSupportKHR(physical_device_, i, surface_, &present),
               "vkGetPhysicalDeviceSurfaceSupportKHR");
    if ((f & VK_QUEUE_GRAPHICS_BIT) && (f & VK_QUEUE_COMPUTE_BIT) && present) {
      queue_family_ = i;
      timestamp_valid_bits_ = families[i].timestampValidBits;
      found = true;
    }
  }
  if (!found)
    throw Error(std::string("device '") + name() + "' has no queue family with graphics and compute" +
                (surface_ != VK_NULL_HANDLE ? " that can present to the window" : ""));

  // Enabled features: what TressVK and the engine need, plus a few optional ones where present that the
  // renderer uses (depth clamp for shadow maps, anisotropic sampling, wireframe debugging).
  VkPhysicalDeviceVulkan13Features en13{};
  en13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  en13.synchronization2 = VK_TRUE;
  en13.dynamicRendering = VK_TRUE;
  VkPhysicalDeviceVulkan12Features en12{};
  en12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  en12.hostQueryReset = have12.hostQueryReset;
  en12.separateDepthStencilLayouts = VK_TRUE;
  en12.pNext = &en13;
  VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR en_stats{};
  en_stats.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR;
  en_stats.pipelineExecutableInfo = VK_TRUE;
  if (pipeline_stats) en13.pNext = &en_stats;
  VkPhysicalDeviceFeatures2 en{};
  en.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  en.pNext = &en12;
  en.features.depthClamp = have.features.depthClamp;
  en.features.samplerAnisotropy = have.features.samplerAnisotropy;
  en.features.fillModeNonSolid = have.features.fillModeNonSolid;
  sampler_anisotropy_ = en.features.samplerAnisotropy == VK_TRUE;
  depth_clamp_ = en.features.depthClamp == VK_TRUE;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{};
  qci.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  qci.queueFamilyIndex = queue_family_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;

  VkDeviceCreateInfo dci{};

  dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  dci.pNext = &en;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  dci.ppEnabledExtensionNames = extensions.data();
  vk_check(vkCreateDevice(physical_device_, &dci, nullptr, &device_), "vkCreateDevice");
  volkLoadDevice(device_);
  vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

  VkCommandPoolCreateInfo pci{};

  pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pci.queueFamilyIndex = queue_family_;
  vk_check(vkCreateCommandPool(device_, &pci, nullptr, &command_pool_), "vkCreateCommandPool");
}

void Device::create_allocator() {
  VmaVulkanFunctions functions{};
  functions.vkGetInstanceProcAddr = vkGetInstanceProcAddr;
  functions.vkGetDeviceProcAddr = vkGetDeviceProcAddr;
  VmaAllocatorCreateInfo info{};
  info.physicalDevice = physical_device_;
  info.device = device_;
  info.instance = instance_;
  info.vulkanApiVersion = api_version_;
  info.pVulkanFunctions = &functions;
  vk_check(vmaCreateAllocator(&info, &allocator_), "vmaCreateAllocator");
}

std::string Device::description() const {
  std::string text = std::string(name()) + " (" + device_type_name(properties_.deviceType) + ", Vulkan " +
                     api_version_string(properties_.apiVersion);
  const std::string driver = driver_text(physical_device_, properties_.apiVersion);
  if (!driver.empty()) text += ", " + driver;
  return text + ")";
}

void Device::run_commands(const std::function<void(VkCommandBuffer)>& record) const {
  VkCommandBufferAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  ai.commandPool = command_pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  vk_check(vkAllocateCommandBuffers(device_, &ai, &cmd), "vkAllocateCommandBuffers");
  VkFence fence = VK_NULL_HANDLE;
  auto cleanup = [&] {
    if (fence) vkDestroyFence(device_, fence, nullptr);
    vkFreeCommandBuffers(device_, command_pool_, 1, &cmd);
  };
  try {
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk_check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
    record(cmd);
    vk_check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkFenceCreateInfo fi{};
    fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    vk_check(vkCreateFence(device_, &fi, nullptr, &fence), "vkCreateFence");
    queue_submit(queue_, cmd, fence);
    vk_check(vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  } catch (...) {
    vkDeviceWaitIdle(device_);
    cleanup();
    throw;
  }
  cleanup();
}

void Device::wait_idle() const { vk_check(vkDeviceWaitIdle(device_), "vkDeviceWaitIdle"); }

void Device::set_name(VkObjectType type, uint64_t handle, const char* object_name) const {
  if (!debug_utils_ || !object_name || !vkSetDebugUtilsObjectNameEXT) return;
  VkDebugUtilsObjectNameInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT;
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = object_name;
  vkSetDebugUtilsObjectNameEXT(device_, &info);
}

}  // namespace tressvk::engine
