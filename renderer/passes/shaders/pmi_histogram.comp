#version 450 core
// PMI: the pixels of each polygon in the item buffer, a_o(v), counted in place on the GPU.
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0, r32ui) uniform readonly uimage2D u_ids;
layout(std430, binding = 0) buffer Counters { uint counts[]; };
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_ids)))) return;
  uint id = imageLoad(u_ids, p).r;
  if (id != 0u) atomicAdd(counts[id - 1u], 1u);
}
