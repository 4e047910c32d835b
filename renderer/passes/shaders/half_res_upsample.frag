#version 450 core
#include "common.glsl"
#include "half_res_upsample.glsl"
#include "ao_fragment.glsl"
