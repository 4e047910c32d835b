#version 450 core
#include "blend.glsl"
layout(location = 0) out vec4 o_no_ao;
layout(location = 1) out vec4 o_with_ao;
layout(location = 2) out vec4 o_ao_only;
void main() { blend(ivec2(gl_FragCoord.xy), o_no_ao, o_with_ao, o_ao_only); }
