#version 450
// tressvk-bench perf's bandwidth reference: a plain copy kernel, 16 bytes a thread per trip through a grid-stride
// loop, to set a frame's bytes against what the GPU's shader cores can move (a transfer command may run on a copy
// engine with a lower ceiling).
layout(local_size_x = 256) in;
layout(std430, set = 0, binding = 0) readonly buffer Src { uvec4 src[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Dst { uvec4 dst[]; };
layout(push_constant) uniform Push { uint count; } pc;  // uvec4 elements to copy

void main() {
  const uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < pc.count; i += stride) dst[i] = src[i];
}
