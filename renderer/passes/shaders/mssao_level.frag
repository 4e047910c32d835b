#version 450 core
#include "common.glsl"
#include "mssao_level.glsl"
layout(location = 0) out vec4 o_ao;
void main() { o_ao = mssao_level(ivec2(gl_FragCoord.xy)); }
