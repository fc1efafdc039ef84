// A well-mixed 32-bit hash of the strand index, in [0, 1): the same strand always gets the same tint, on the
// raster path (hair_expand.glsl) and the compute path (compute/vertex_input.glsl) alike.
float strand_hash(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return float(x) * (1.0 / 4294967296.0);
}
