// The pictures the report draws beside its data, made from the images its cases keep: a PNG
// preview of each image a browser cannot show (EXR, Radiance HDR, TIFF, Targa), and
// thumbnails. Both are written beside the image they show, inside the report's case folders
// only (never into a goldens folder), and only for images the report shows.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "image/picture.hpp"

namespace aosuite::harness {

// Whether `rel` names a plain file inside `dir` (no link, no ..): a report never shows
// anything else on the machine.
bool inside(const std::filesystem::path& dir, const std::string& rel);

// A picture as a screen shows it, 8-bit sRGB RGBA: 8-bit images as they are; float ones times
// 2^-stops, clamped to [0, 1] (NaN as 0) and, when linear (EXR, HDR, float TIFF), sRGB-encoded,
// with no other tone mapping; one channel as grey.
RgbaImage display_rgba8(const Picture& p, int stops = 0);

// How many stops a linear float picture's preview is darkened by so that its highlights are not
// clipped: the least k >= 0 (at most 24) with the 99.9th percentile of its finite samples
// <= 2^k (a few fireflies still clip). 0 for 8-bit and sRGB-encoded (16-bit) pictures. The
// page's exposure control brings the light back.
int preview_stops(const Picture& p);

// The stops a preview named by shown_image() is darkened by: k for `….s<k>.png`.
int stops_of_preview(const std::string& rel);

// What the page shows for the image `rel` (relative to `dir`): `rel` itself when a browser
// shows its format, else its PNG preview beside it, `<file name>.<hash>.s<k>.png` (darkened by
// k stops, preview_stops()), named by the
// hash of the image's bytes: an image that changes (a later run, a bless, a copied report)
// gets a preview of its own, and the old one is removed. Empty when `rel` is no plain file
// inside `dir` or cannot be read.
std::string shown_image(const std::filesystem::path& dir, const std::string& rel);

// What the report draws over a diff to show the pixels a tolerance ignored (ignored_pixels():
// width * height flags): those pixels a translucent blue, their outline opaque, the rest
// transparent.
RgbaImage ignored_overlay(std::span<const std::uint8_t> ignored, int width, int height);

// A thumbnail of the PNG `rel` (relative to `dir`) at most 160x120: the image itself when it is
// that small, else thumb_<name> beside it (made again when older than it). Empty when `rel`
// cannot be read.
std::string thumbnail(const std::filesystem::path& dir, const std::string& rel);

}  // namespace aosuite::harness
