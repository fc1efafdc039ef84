#include <tressvk/engine/descriptors.hpp>
#include <tressvk/test/vulkan.hpp>

#include <catch2/catch_test_macros.hpp>

using namespace tressvk;

TEST_CASE("samplers for colour and shadow-map lookups are created validation-clean", "[vulkan][engine]") {
  engine::Device& dev = test::device();
  const auto linear = engine::create_sampler(dev);
  CHECK(static_cast<bool>(linear));
  engine::SamplerDesc shadow;
  shadow.compare = true;
  shadow.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
  const auto compare = engine::create_sampler(dev, shadow);
  CHECK(static_cast<bool>(compare));
  // Anisotropy above the device limit is clamped, and ignored when the feature is absent, never invalid.
  engine::SamplerDesc aniso;
  aniso.max_anisotropy = 1e6f;
  const auto clamped = engine::create_sampler(dev, aniso);
  CHECK(static_cast<bool>(clamped));
  CHECK(test::validation_message_count() == 0);
}
