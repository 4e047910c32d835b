// What kind of change a failing comparison saw (blazediff's `interpret`, for a renderer): the
// changed pixels grouped into connected regions, each named as a shift (with its offset), a
// brightness or colour change (with its mean difference), content added or removed, or noise.
// A reviewer reads "shift by (+1, 0)" before opening the images.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "image/rgba_image.hpp"

namespace aosuite::comparison {

enum class ChangeKind { kShift, kBrightness, kColour, kOpacity, kAdded, kRemoved, kNoise, kOther };
std::string_view change_kind_name(ChangeKind k);  // "shift", "brightness", "colour", ...

struct ChangedRegion {
  ChangeKind kind = ChangeKind::kOther;
  int left = 0, top = 0, width = 0, height = 0;  // the region's bounding box
  long long pixels = 0;                          // changed pixels in it
  int dx = 0, dy = 0;                            // kShift: how far the content moved
  // The mean signed difference, actual - expected, of R, G and B, in levels (kBrightness,
  // kColour), or of alpha in all three (kOpacity); for the others the mean largest
  // |difference| of a pixel's R, G, B, in all three.
  double mean[3] = {0, 0, 0};
  std::string text() const;  // "shift by (+1, 0) px, 40x12 at (10, 20)"
};

// The changed pixels (any channel differs) of two images of one size, as regions: the largest
// `max_regions` by pixel count, then scattered pixels (components under 8 pixels) as one kNoise
// region. `ignored` (width * height flags, or empty) leaves pixels out. Nothing (no regions)
// where the analysis would take more than `max_bytes` (13 bytes a pixel): a failing pair is
// described within the memory limit its images were decoded under, or not at all.
std::vector<ChangedRegion> changed_regions(const RgbaImage& expected, const RgbaImage& actual,
                                           const std::vector<std::uint8_t>& ignored = {},
                                           int max_regions = 8,
                                           std::uint64_t max_bytes = UINT64_MAX);

// As results.json and `compare --json` hold them: {"kind": "shift", "text": ..., "left": ...};
// reading takes what it knows (an unknown kind is kOther).
nlohmann::json changes_json(const std::vector<ChangedRegion>& regions);
std::vector<ChangedRegion> changes_from_json(const nlohmann::json& j);

// "shift by (+1, 0) px, 40x12 at (10, 20); brighter by 5.1 levels, ..." (at most `shown`).
std::string changes_text(const std::vector<ChangedRegion>& regions, std::size_t shown = 3);

}  // namespace aosuite::comparison
