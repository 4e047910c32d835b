#version 450 core
// Gouraud interpolation of the per-vertex PMI visibility, as the paper displays it.
in float v_visibility;
layout(location = 0) out float o_ao;
void main() { o_ao = clamp(v_visibility, 0.0, 1.0); }
