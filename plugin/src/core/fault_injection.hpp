// Fault injection for tests: a private link of TvkContextCreateInfo::next (not in the public headers, never
// documented to hosts) makes the context route every fallible Vulkan call it makes -- its own and VMA's --
// through counting wrappers that fail the Nth one with an error that call can return. Without the link the
// device table is left as loaded and nothing is counted. One fault-injected context per process at a time.
#pragma once

#include <volk.h>

#include <cstdint>

namespace tressvk::fault {

inline constexpr uint32_t kChainType = 0x4B465654u;  // "TVFK"

struct Control {
  uint64_t fail_at = 0;          // fail the fail_at-th fallible call counted from now (1 = the next); 0 = never
  uint64_t calls = 0;            // fallible calls counted so far
  const char* fired = nullptr;   // the call that was failed, once it was
  bool device_lost = false;      // from now on the calls that can report a lost device (vkGetQueryPoolResults) do
  void arm(uint64_t nth) {
    fail_at = nth;
    calls = 0;
    fired = nullptr;
  }
};

struct ChainLink {
  uint32_t type = kChainType;
  const void* next = nullptr;
  Control* control = nullptr;
};

// Wraps the fallible entries of `table` when the `next` chain carries a ChainLink; otherwise does nothing.
void install(const void* next, VolkDeviceTable& table);

}  // namespace tressvk::fault
