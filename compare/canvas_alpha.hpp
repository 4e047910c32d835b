// What a 2D canvas does to a decoded image before Resemble.js sees it. Canvases store
// premultiplied 8-bit colour, so translucent pixels come back from getImageData slightly
// changed. Opaque pixels are never touched. Models measured against the real engines (Chromium,
// node-canvas 2.11.2); the oracle_differential test checks Chromium's on every run against
// Resemble.js in Chromium itself (tests/oracles/resemble).
#pragma once

#include <string_view>

#include "image/rgba_image.hpp"

namespace aosuite {

enum class CanvasAlpha {
  kNone,       // compare the PNG's own bytes (what Resemble sees for opaque images)
  kChromium,   // Resemble.js in Chromium: premultiply, unpremultiply in float32
  kNodeCanvas  // Resemble.js in Node with node-canvas 2.x: unpremultiply truncates
};

CanvasAlpha parse_canvas_alpha(std::string_view name);  // throws std::invalid_argument

// The drawImage + getImageData round trip, in place.
void apply_canvas_decode(RgbaImage& rgba, CanvasAlpha model);

// node-canvas's extra putImageData + getImageData round trip that Resemble's normalise()
// applies to images padded to a common size. The identity in Chromium.
void apply_canvas_put_get(RgbaImage& rgba, CanvasAlpha model);

}  // namespace aosuite
