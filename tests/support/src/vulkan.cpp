// The shared Vulkan test fixture (see include/tressvk/test/vulkan.hpp). Everything lives in this one
// translation unit on purpose: the Catch2 listener below is registered by a static object, and a static
// library only contributes object files that something references. Every helper here references device(),
// so any test that uses the fixture links the listener too.
#include <tressvk/test/vulkan.hpp>

#include <catch2/catch_test_case_info.hpp>
#include <catch2/catch_test_macros.hpp>
#include <catch2/reporters/catch_reporter_event_listener.hpp>
#include <catch2/reporters/catch_reporter_registrars.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>

namespace tressvk::test {

namespace {

struct FixtureState {
  std::mutex mutex;
  std::unique_ptr<engine::Device> device;
  std::shared_ptr<engine::MessageLog> log;
  std::string creation_error;  // set once when creation failed; later calls fail the same way at once
  bool in_test_case = false;
  std::thread::id test_thread;
  std::string test_name;
  // The active expectation (nullptr when none) and what it captured.
  ExpectedValidationMessages* expectation = nullptr;
  std::string expectation_filter;
  std::vector<engine::ValidationMessage> captured;
  // Messages that could not fail a test case directly (outside a test, or from another thread).
  std::vector<std::string> unreported;
};

FixtureState& fixture() {
  static FixtureState state;
  return state;
}

// Decides what a counted validation message does. Returns true when it was turned into a test failure or
// captured (so the engine does not print it a second time).
bool on_validation_message(const engine::ValidationMessage& message) {
  FixtureState& f = fixture();
  const std::string text = engine::format_message(message);
  bool fail_now = false;
  {
    std::lock_guard lock(f.mutex);
    const bool on_test_thread = f.in_test_case && std::this_thread::get_id() == f.test_thread;
    if (f.expectation && on_test_thread) {
      const bool matches = f.expectation_filter.empty() ||
                           message.id_name.find(f.expectation_filter) != std::string::npos ||
                           message.text.find(f.expectation_filter) != std::string::npos;
      if (matches) {
        f.captured.push_back(message);
        std::printf("(expected) %s\n", text.c_str());
        return true;
      }
      fail_now = true;
    } else if (on_test_thread) {
      fail_now = true;
    } else {
      f.unreported.push_back(f.test_name.empty() ? text : "during '" + f.test_name + "': " + text);
      return false;
    }
  }
  // Outside the lock: a failing assertion may unwind into code that takes it again.
  if (fail_now) FAIL_CHECK("Vulkan validation message: " << text);
  return true;
}

engine::Device& create_device_locked(FixtureState& f) {
  engine::DeviceOptions options;
  options.app_name = "tressvk-tests";
  options.validation = true;
  options.sync_validation = true;
  options.print_messages = true;
  try {
    auto dev = std::make_unique<engine::Device>(host::with_plugin_requirements(options));
    f.log = dev->message_log();
    f.log->set_hook(on_validation_message);
    std::printf("TressVK tests: device %s, validation + synchronization validation on\n",
                dev->description().c_str());
    std::fflush(stdout);
    f.device = std::move(dev);
  } catch (const std::exception& e) {
    f.creation_error = std::string("cannot create the Vulkan test device: ") + e.what();
    throw engine::Error(f.creation_error);
  }
  return *f.device;
}

// Tracks the running test case and tears the device down at the end of the run, while a failure can still
// change the process's exit status.
class VulkanFixtureListener : public Catch::EventListenerBase {
 public:
  using Catch::EventListenerBase::EventListenerBase;

  void testCaseStarting(const Catch::TestCaseInfo& info) override {
    FixtureState& f = fixture();
    std::lock_guard lock(f.mutex);
    f.in_test_case = true;
    f.test_thread = std::this_thread::get_id();
    f.test_name = info.name;
  }

  void testCaseEnded(const Catch::TestCaseStats&) override {
    FixtureState& f = fixture();
    std::lock_guard lock(f.mutex);
    f.in_test_case = false;
  }

  void testRunEnded(const Catch::TestRunStats&) override {
    FixtureState& f = fixture();
    std::unique_ptr<engine::Device> dev;
    {
      std::lock_guard lock(f.mutex);
      dev = std::move(f.device);
      f.test_name = "device teardown";
    }
    dev.reset();  // vkDestroyDevice / vkDestroyInstance: the layer reports leaked objects here
    std::lock_guard lock(f.mutex);
    if (!f.unreported.empty()) {
      std::fprintf(stderr, "TressVK tests: %zu validation message(s) outside a running test case (device teardown, other threads):\n",
                   f.unreported.size());
      for (const std::string& m : f.unreported) std::fprintf(stderr, "  %s\n", m.c_str());
      std::fflush(stderr);
      std::fflush(stdout);
      std::_Exit(1);  // Catch2 has already tallied its results; only the exit status can still say "failed"
    }
  }
};

}  // namespace

CATCH_REGISTER_LISTENER(VulkanFixtureListener)

engine::Device& device() {
  FixtureState& f = fixture();
  std::lock_guard lock(f.mutex);
  if (f.device) return *f.device;
  if (!f.creation_error.empty()) throw engine::Error(f.creation_error);
  return create_device_locked(f);
}

void run_commands(const std::function<void(VkCommandBuffer)>& record) { device().run_commands(record); }

engine::Buffer make_buffer(VkDeviceSize bytes, VkBufferUsageFlags usage, engine::MemoryUsage memory) {
  return engine::create_buffer(device(), bytes, usage, memory);
}

namespace {
void on_plugin_message(TvkMessageSeverity severity, const char* message, void* user_data) {
  const char* level = severity == TVK_MESSAGE_ERROR ? "error" : severity == TVK_MESSAGE_WARNING ? "warning" : "info";
  std::printf("[tressvk %s] %s\n", level, message);
  if (severity == TVK_MESSAGE_ERROR && user_data) *static_cast<std::string*>(user_data) = message;
}
}  // namespace

void PluginContextDeleter::operator()(TvkContext context) const {
  if (!context) return;
  vkDeviceWaitIdle(device().device());
  tressvk_destroy_context(context);
}

PluginContext create_plugin_context(uint32_t frames_in_flight) {
  engine::Device& dev = device();
  static std::string last_error;  // outlives the context: the callback may run until destruction
  TvkContextCreateInfo info = host::context_info(dev);
  info.frames_in_flight = frames_in_flight;
  info.message_callback = on_plugin_message;
  info.message_user_data = &last_error;
  TvkContext context = nullptr;
  last_error.clear();
  const TvkResult r = tressvk_create_context(&info, &context);
  INFO("tressvk_create_context: " << tressvk_result_string(r) << (last_error.empty() ? "" : ": ") << last_error);
  REQUIRE(r == TVK_SUCCESS);
  REQUIRE(context != nullptr);
  return PluginContext(context);
}

uint64_t validation_message_count() { return device().messages().count(); }

ExpectedValidationMessages::ExpectedValidationMessages(uint64_t min_count, std::string id_contains)
    : min_count_(min_count), id_contains_(std::move(id_contains)) {
  device();  // the device must exist (and be validated) before the expectation starts
  FixtureState& f = fixture();
  std::lock_guard lock(f.mutex);
  if (f.expectation) throw engine::Error("expect_validation_messages: expectations cannot nest");
  f.expectation = this;
  f.expectation_filter = id_contains_;
  f.captured.clear();
}

ExpectedValidationMessages::~ExpectedValidationMessages() {
  FixtureState& f = fixture();
  uint64_t captured = 0;
  {
    std::lock_guard lock(f.mutex);
    f.expectation = nullptr;
    captured = f.captured.size();
  }
  if (std::uncaught_exceptions() > 0) return;  // the test already failed; do not pile on
  INFO("expected at least " << min_count_ << " validation message(s)"
                            << (id_contains_.empty() ? std::string() : " containing '" + id_contains_ + "'"));
  CHECK(captured >= min_count_);
}

uint64_t ExpectedValidationMessages::count() const {
  FixtureState& f = fixture();
  std::lock_guard lock(f.mutex);
  return f.captured.size();
}

std::vector<engine::ValidationMessage> ExpectedValidationMessages::messages() const {
  FixtureState& f = fixture();
  std::lock_guard lock(f.mutex);
  return f.captured;
}

std::filesystem::path data_file(const std::filesystem::path& relative) {
  const char* env = std::getenv("TRESSVK_DATA_DIR");
  if (!env || !*env) SKIP("TRESSVK_DATA_DIR is not set; real hair data is needed for this test");
  const std::filesystem::path path = std::filesystem::path(env) / relative;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) SKIP("real hair data not found: " << path.string());
  return path;
}

std::filesystem::path output_dir() {
  const char* env = std::getenv("TRESSVK_TEST_OUTPUT");
  const std::filesystem::path dir = env && *env ? std::filesystem::path(env) : std::filesystem::path("test-output");
  std::filesystem::create_directories(dir);
  return std::filesystem::absolute(dir);
}

}  // namespace tressvk::test
