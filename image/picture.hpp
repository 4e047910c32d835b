// An image as the metrics take it, whatever file it came from: 8-bit sRGB RGBA (8-bit PNGs,
// JPEG, WebP, ..., as Resemble.js and FLIP's LDR mode see them) or float samples (EXR, Radiance
// HDR and float TIFF as linear light; 16-bit PNG and TIFF kept at 16 bits, sRGB-encoded). Float
// images hold one channel (grey, Y) or three (R, G, B), interleaved.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "image/rgba_image.hpp"

namespace aosuite {

struct Picture {
  std::string name;    // the file, for messages
  std::string format;  // "PNG", "EXR", "JPEG", "TIFF", "WebP", "Radiance HDR", ...
  bool is_float = false;
  RgbaImage rgba;     // !is_float
  FloatImage floats;  // is_float
  ImageSize size() const;
  // What the image is, for messages: "8-bit RGBA", "16-bit PNG, 3 channels", "EXR, 1 channel".
  std::string kind() const;
};

// Whether two pictures hold the same kind of samples (8-bit; 16-bit sRGB; linear float), with
// as many channels or grey against R, G, B, whatever their file formats: what a metric can
// compare. Grey counts as R = G = B at every depth, as an 8-bit grey file decodes to RGBA.
bool same_kind(const Picture& a, const Picture& b);
// A one-channel (grey) float image as three equal channels; others as they are.
void widen_grey(FloatImage& f);

// The image formats aosuite reads: PNG and EXR itself, the others through OpenImageIO
// (libaosuite_oiio.so, opened on the first such file). For messages.
inline constexpr const char* kImageFormats =
    "PNG, EXR, JPEG, TIFF (8, 16-bit, float), WebP, Radiance HDR, Targa, BMP, GIF (its first "
    "frame)";
// Whether a file name's extension is one of theirs (folder mode pairs these).
bool is_image_name(const std::filesystem::path& name);

// An 8-bit RGBA view of a picture as a browser canvas holds it, which is what Resemble.js
// compares: 8-bit images as they are, 16-bit ones by their high byte (as aosuite's PNG
// decoder reduces a 16-bit PNG). Throws FileError for a float (linear) image, which a canvas
// cannot hold.
RgbaImage canvas_rgba8(const Picture& p);

// Whether these bytes start a PNG file, an OpenEXR file.
bool is_png(std::span<const unsigned char> bytes);
bool is_exr(std::span<const unsigned char> bytes);

// A float image of an RGBA8 one: R, G, B as v / 255, still sRGB-encoded.
FloatImage to_float(RgbaView rgba);

}  // namespace aosuite
