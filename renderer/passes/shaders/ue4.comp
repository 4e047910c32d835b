#version 450 core
#include "common.glsl"
#include "ue4.glsl"
#include "ao_compute.glsl"
