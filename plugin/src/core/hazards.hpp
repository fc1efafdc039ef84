// Derives the barriers between simulation passes from what each pass reads and writes, so that every barrier is
// scoped to exactly the buffers that need it. Bindings are numbered as in shaders/sim/layout.glsl; a mask has
// bit b set for binding b.
//
// Rules (all passes run in the compute stage):
// - read-after-write and write-after-write on binding b: a buffer memory barrier on b
//   (SHADER_STORAGE_WRITE -> SHADER_STORAGE_READ|WRITE);
// - write-after-read only: an execution dependency, recorded as an access-free buffer barrier on b.
// Each buffer is tracked on its own: a barrier on one buffer is not counted as ordering another buffer's
// accesses, even where the execution dependency it creates would (synchronization validation tracks hazards per
// resource, and being explicit keeps every dependency visible in the recorded commands).
#pragma once

#include <cstdint>

namespace tressvk {

struct HazardTracker {
  uint32_t pending_writes = 0;  // written since the last barrier that named the binding
  uint32_t pending_reads = 0;   // read since the last barrier of any kind

  struct Need {
    uint32_t memory = 0;     // bindings that need a memory barrier before the next pass
    uint32_t execution = 0;  // bindings that need only an execution dependency (write-after-read)
    bool any() const { return (memory | execution) != 0; }
  };

  Need before(uint32_t reads, uint32_t writes) const {
    Need need;
    need.memory = pending_writes & (reads | writes);
    need.execution = pending_reads & writes & ~need.memory;
    return need;
  }
  // Call after the barriers of `need` were recorded.
  void barrier_recorded(const Need& need) {
    pending_writes &= ~need.memory;
    pending_reads &= ~(need.memory | need.execution);
  }
  void pass_recorded(uint32_t reads, uint32_t writes) {
    pending_reads |= reads;
    pending_writes |= writes;
  }
};

}  // namespace tressvk
