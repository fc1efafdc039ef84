#version 450
// tressvk-bench's clock probe: one workgroup running a chain of dependent multiply-adds, so its time is the shader
// cores' clock period times a fixed count. A warm-up is over only once the probe runs as fast as it has in this
// process (frame_timing.cpp): a GPU whose clock fell while the host was busy reads slow until it climbs back.
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) writeonly buffer Sink { float sink[]; };
layout(push_constant) uniform Push { uint iterations; float seed; } pc;

void main() {
  float x = pc.seed + float(gl_LocalInvocationID.x) * 1.0e-7;
  for (uint i = 0u; i < pc.iterations; ++i) x = fma(x, 0.9999999, 1.0e-7);
  if (x == 12345.0) sink[gl_LocalInvocationID.x] = x;  // never: keeps the chain from being optimised away
}
