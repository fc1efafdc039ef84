// The simulation's blocked vertex layout (shaders/sim/layout.glsl; TVK_STRAND_BLOCK = 32 in tressvk.h): the element of
// vertex v of strand s, strands of n vertices. Both hair paths read a strand's positions at its own elements and its
// tangents at its guide's (the simulation stores the guides' tangents only: a follow hair's is its guide's).
#ifndef TRESSVK_RENDER_STRAND_LAYOUT_GLSL
#define TRESSVK_RENDER_STRAND_LAYOUT_GLSL
uint strand_element(uint s, uint v, uint n) { return (s / 32u) * (32u * n) + v * 32u + s % 32u; }
#endif
