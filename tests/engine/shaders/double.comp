#version 450
// Test shader: data[i] *= 2 for i < count. The workgroup size is specialization constant 0.
layout(local_size_x_id = 0) in;

layout(std430, set = 0, binding = 0) buffer Data { float data[]; };
layout(push_constant) uniform Push { uint count; } pc;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i < pc.count) data[i] *= 2.0;
}
