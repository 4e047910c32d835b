#version 450 core
#include "common.glsl"
#include "alchemy.glsl"
#include "ao_compute.glsl"
