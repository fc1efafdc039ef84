// Contexts with the plugin's fault-injection hook (plugin/src/core/fault_injection.hpp) in their `next` chain: the
// hook counts the fallible Vulkan calls the context makes in `control` and fails the one it is armed for.
#pragma once

#include "core/fault_injection.hpp"

#include <tressvk/host/glue.hpp>
#include <tressvk/test/vulkan.hpp>

#include <catch2/catch_test_macros.hpp>

namespace tressvk::test {

// A TvkContextCreateInfo for the test device that chains `link` (pointed at `control`); both must outlive the
// tressvk_create_context call.
inline TvkContextCreateInfo fault_injecting_context_info(fault::Control& control, fault::ChainLink& link) {
  link.control = &control;
  TvkContextCreateInfo info = host::context_info(device());
  info.next = &link;
  return info;
}

// The same context, created (REQUIRE): `frames_in_flight` 0 is the plugin's default.
inline TvkContext create_fault_injecting_context(fault::Control& control, fault::ChainLink& link,
                                                 uint32_t frames_in_flight, bool timestamps) {
  TvkContextCreateInfo info = fault_injecting_context_info(control, link);
  info.frames_in_flight = frames_in_flight;
  info.enable_timestamps = timestamps ? VK_TRUE : VK_FALSE;
  TvkContext ctx = nullptr;
  REQUIRE(tressvk_create_context(&info, &ctx) == TVK_SUCCESS);
  return ctx;
}

}  // namespace tressvk::test
