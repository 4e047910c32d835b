#version 450 core
#include "common.glsl"
#include "sao.glsl"
#include "ao_fragment.glsl"
