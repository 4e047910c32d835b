// What every AO estimator reads, as one std140 block at binding 0. Its C++ twin is
// renderer/ao_uniforms.hpp (static_asserts hold the offsets, and a renderer test compares them
// with the linked programs'), filled once per draw by ao_uniform_block().
layout(std140, binding = 0) uniform AoUniforms {
  int u_samples;              // taps per pixel (not GTAO)
  float u_radius;             // world-space radius
  float u_bias;               // each shader's header says which
  float u_intensity;          // sigma
  float u_contrast;           // k (Alchemy, SAO), power (UE4), final power (GTAO)
  float u_turns;              // spiral turns (Alchemy, SAO)
  float u_max_pixel_radius;   // MSSAO's per-level cap; unbounded elsewhere
  float u_proj_scale;         // pixels per unit at unit distance: H / (2 tan(fovy/2))
  int u_slices;               // GTAO, bitmask
  int u_steps;                // GTAO, bitmask: per side
  float u_falloff_range;      // GTAO: share of the radius over which occluders fade out
  float u_thin_occluder;      // GTAO: XeGTAO's ThinOccluderCompensation
  float u_thickness;          // bitmask: every occluder's assumed thickness, share of u_radius
  int u_exact_plane;          // GTAO: samples on the slice, arcs over an open plane's
};
