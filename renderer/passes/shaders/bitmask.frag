#version 450 core
#include "common.glsl"
#include "bitmask.glsl"
#include "ao_fragment.glsl"
