// The sRGB transfer function (IEC 61966-2-1), in float, as every reader of sRGB bytes here
// applies it: FLIP's LDR input (as NVlabs/flip's tool does), float pictures marked sRGB, and the
// reference frame that reproduces blend.frag's output on the CPU.
#pragma once

#include <algorithm>
#include <cmath>

namespace aosuite {

// Encoded value in [0, 1] -> linear.
inline float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Linear -> encoded, clamped to [0, 1] first (blend.glsl's to_srgb on an 8-bit target).
inline float linear_to_srgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c < 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace aosuite
