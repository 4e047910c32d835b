#version 450 core
// Gouraud interpolation of the per-vertex PMI visibility, as the paper displays it, through
// the affine-and-power map `aosuite tune` fits to the ray-traced AO (ao-techniques.md §7.3:
// PMI is scaled differently from AO): u_intensity scales the occlusion 1 - visibility, and
// u_contrast is the power of what is left. At 1 and 1 it is the paper's map.
in float v_visibility;
uniform float u_intensity;
uniform float u_contrast;  // > 0 (params.cpp), so pow(0, c) is 0
layout(location = 0) out float o_ao;
void main() {
  float occlusion = 1.0 - clamp(v_visibility, 0.0, 1.0);
  o_ao = pow(clamp(1.0 - u_intensity * occlusion, 0.0, 1.0), u_contrast);
}
