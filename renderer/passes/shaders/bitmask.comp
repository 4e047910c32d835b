#version 450 core
#include "common.glsl"
#include "bitmask.glsl"
#include "ao_compute.glsl"
