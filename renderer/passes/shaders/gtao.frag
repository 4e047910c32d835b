#version 450 core
#include "common.glsl"
#include "gtao.glsl"
#include "ao_fragment.glsl"
