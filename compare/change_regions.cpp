#include "compare/change_regions.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace aosuite::comparison {

namespace {

// Components smaller than this are scattered pixels (noise), not a region of their own.
constexpr long long kSmallRegion = 8;
// The offsets a shift is looked for within, in pixels (rasterisation moves things by 1-2).
constexpr int kShiftReach = 3;
// Pixels a region's shift test samples at most (evenly): enough to tell, bounded in time.
constexpr std::size_t kShiftSamples = 20000;
// A uniform offset larger than this (in levels) where the expected image showed the background
// around it is content added, not a change of brightness.
constexpr double kLargeOffset = 32;
// What the analysis holds at most, per pixel: a state byte, a 4-byte index in its component and
// up to 4 in the search's stack, and the scattered pixels' list.
constexpr std::uint64_t kAnalysisBytesPerPixel = 13;

struct Component {
  std::vector<std::uint32_t> pixels;  // row-major indices (images stay under 2^32 pixels)
  int left = 0, top = 0, right = 0, bottom = 0;
};

// 8-connected components of the changed pixels. `changed` (0 unchanged, 1 changed) marks the
// pixels it has visited 2, so that the analysis holds one byte a pixel beside the indices.
std::vector<Component> components(std::vector<std::uint8_t>& changed, int w, int h) {
  std::vector<Component> out;
  std::vector<std::uint32_t> stack;
  for (std::size_t start = 0; start < changed.size(); ++start) {
    if (changed[start] != 1) continue;
    Component c;
    c.left = c.right = int(start % std::size_t(w));
    c.top = c.bottom = int(start / std::size_t(w));
    changed[start] = 2;
    stack.assign(1, std::uint32_t(start));
    while (!stack.empty()) {
      const std::uint32_t i = stack.back();
      stack.pop_back();
      c.pixels.push_back(i);
      const int x = int(i % std::uint32_t(w)), y = int(i / std::uint32_t(w));
      c.left = std::min(c.left, x), c.right = std::max(c.right, x);
      c.top = std::min(c.top, y), c.bottom = std::max(c.bottom, y);
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
          const std::size_t j = std::size_t(yy) * std::size_t(w) + std::size_t(xx);
          if (changed[j] == 1) changed[j] = 2, stack.push_back(std::uint32_t(j));
        }
      }
    }
    out.push_back(std::move(c));
  }
  return out;
}

int channel(const RgbaImage& img, std::size_t i, int c) { return img.data()[4 * i + c]; }

// The largest |a - b| of R, G, B between two pixels.
int pixel_delta(const RgbaImage& a, std::size_t i, const RgbaImage& b, std::size_t j) {
  int d = 0;
  for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(channel(a, i, c) - channel(b, j, c)));
  return d;
}

// The offset (dx, dy) by which the region's content moved, if moving the expected image by it
// explains the actual pixels far better than not moving it; else (0, 0).
std::pair<int, int> shift_of(const Component& c, const RgbaImage& e, const RgbaImage& a,
                             double unmoved) {
  const int w = e.width(), h = e.height();
  const std::size_t step = std::max<std::size_t>(1, c.pixels.size() / kShiftSamples);
  double best = unmoved;
  std::pair<int, int> moved{0, 0};
  for (int dy = -kShiftReach; dy <= kShiftReach; ++dy) {
    for (int dx = -kShiftReach; dx <= kShiftReach; ++dx) {
      if (dx == 0 && dy == 0) continue;
      double sum = 0;
      std::size_t n = 0;
      for (std::size_t k = 0; k < c.pixels.size(); k += step, ++n) {
        const std::size_t i = c.pixels[k];
        const int x = int(i % std::size_t(w)) - dx, y = int(i / std::size_t(w)) - dy;
        sum += x < 0 || y < 0 || x >= w || y >= h
                   ? 255.0
                   : pixel_delta(a, i, e, std::size_t(y) * std::size_t(w) + std::size_t(x));
      }
      const double err = sum / double(std::max<std::size_t>(n, 1));
      if (err < best) best = err, moved = {dx, dy};
    }
  }
  // Exact up to a level, or a tenth of the unmoved difference: the content moved.
  return best <= std::max(1.0, 0.1 * unmoved) ? moved : std::pair<int, int>{0, 0};
}

// The mean largest |pixel - colour| of R, G, B over the region in `img`.
double distance_to(const Component& c, const RgbaImage& img, const double colour[3]) {
  double sum = 0;
  for (const std::size_t i : c.pixels) {
    double d = 0;
    for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(channel(img, i, k) - colour[k]));
    sum += d;
  }
  return sum / double(c.pixels.size());
}

// The mean colour of the unchanged pixels in a 2-pixel ring around the region (the background
// it sits on), in the expected image; false if it has no such pixels.
bool surroundings(const Component& c, const std::vector<std::uint8_t>& changed, const RgbaImage& e,
                  double colour[3]) {
  const int w = e.width(), h = e.height();
  double sum[3] = {0, 0, 0};
  long long n = 0;
  for (int y = std::max(0, c.top - 2); y <= std::min(h - 1, c.bottom + 2); ++y) {
    for (int x = std::max(0, c.left - 2); x <= std::min(w - 1, c.right + 2); ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
      if (changed[i]) continue;
      for (int k = 0; k < 3; ++k) sum[k] += channel(e, i, k);
      ++n;
    }
  }
  for (int k = 0; k < 3; ++k) colour[k] = n ? sum[k] / double(n) : 0;
  return n > 0;
}

ChangedRegion classify(const Component& c, const std::vector<std::uint8_t>& changed,
                       const RgbaImage& e, const RgbaImage& a) {
  ChangedRegion r;
  r.left = c.left, r.top = c.top, r.width = c.right - c.left + 1, r.height = c.bottom - c.top + 1;
  r.pixels = static_cast<long long>(c.pixels.size());
  const double n = double(c.pixels.size());
  double mean[3] = {0, 0, 0}, largest = 0;
  for (const std::size_t i : c.pixels) {
    for (int k = 0; k < 3; ++k) mean[k] += channel(a, i, k) - channel(e, i, k);
    largest += pixel_delta(a, i, e, i);
  }
  for (double& m : mean) m /= n;
  largest /= n;
  double residual = 0;  // how far the difference is from one uniform offset
  for (const std::size_t i : c.pixels) {
    for (int k = 0; k < 3; ++k) residual += std::abs(channel(a, i, k) - channel(e, i, k) - mean[k]);
  }
  residual /= 3 * n;
  const auto mean_of = [&r](const double m[3]) { std::copy(m, m + 3, r.mean); };
  // Transparency that changed more than the colour did: the colour channels cannot say it.
  double alpha = 0, alpha_size = 0;
  for (const std::size_t i : c.pixels) {
    alpha += channel(a, i, 3) - channel(e, i, 3);
    alpha_size += std::abs(channel(a, i, 3) - channel(e, i, 3));
  }
  if (alpha_size / n > largest) {
    r.kind = ChangeKind::kOpacity;
    r.mean[0] = r.mean[1] = r.mean[2] = alpha / n;
    return r;
  }
  const double strongest = std::max({std::abs(mean[0]), std::abs(mean[1]), std::abs(mean[2])});

  if (const auto [dx, dy] = shift_of(c, e, a, largest); dx != 0 || dy != 0) {
    r.kind = ChangeKind::kShift, r.dx = dx, r.dy = dy;
    r.mean[0] = r.mean[1] = r.mean[2] = largest;
    return r;
  }
  const bool uniform = strongest >= 1 && residual <= std::max(1.0, 0.2 * strongest);
  const auto offset = [&] {
    const double low = std::min({mean[0], mean[1], mean[2]});
    const double high = std::max({mean[0], mean[1], mean[2]});
    const bool grey = (low > 0) == (high > 0) && high - low <= std::max(1.0, 0.25 * strongest);
    r.kind = grey ? ChangeKind::kBrightness : ChangeKind::kColour;
    mean_of(mean);
    return r;
  };
  // A uniform offset of a few levels is a brightness or colour change, wherever it is.
  if (uniform && strongest <= kLargeOffset) return offset();
  r.mean[0] = r.mean[1] = r.mean[2] = largest;
  if (double background[3];
      c.pixels.size() >= 2 * kSmallRegion && surroundings(c, changed, e, background)) {
    // Content where the expected image showed its background (added), or the background where
    // it showed content (removed).
    const double was = distance_to(c, e, background), is = distance_to(c, a, background);
    if (was <= 0.3 * is) return r.kind = ChangeKind::kAdded, r;
    if (is <= 0.3 * was) return r.kind = ChangeKind::kRemoved, r;
  }
  if (uniform) return offset();
  // Small differences that shift nothing on average: noise.
  const bool unbiased = std::abs(mean[0] + mean[1] + mean[2]) / 3 <= 0.3 * largest;
  r.kind = largest <= 8 && unbiased ? ChangeKind::kNoise : ChangeKind::kOther;
  return r;
}

}  // namespace

std::string_view change_kind_name(ChangeKind k) {
  switch (k) {
    case ChangeKind::kShift:
      return "shift";
    case ChangeKind::kBrightness:
      return "brightness";
    case ChangeKind::kColour:
      return "colour";
    case ChangeKind::kOpacity:
      return "opacity";
    case ChangeKind::kAdded:
      return "added";
    case ChangeKind::kRemoved:
      return "removed";
    case ChangeKind::kNoise:
      return "noise";
    case ChangeKind::kOther:
      break;
  }
  return "other";
}

std::string ChangedRegion::text() const {
  std::string what;
  switch (kind) {
    case ChangeKind::kShift:
      what = fmt::format("shift by ({:+d}, {:+d}) px", dx, dy);
      break;
    case ChangeKind::kBrightness: {
      const double m = (mean[0] + mean[1] + mean[2]) / 3;
      what = fmt::format("{} by {:.1f} levels", m > 0 ? "brighter" : "darker", std::abs(m));
      break;
    }
    case ChangeKind::kColour:
      what = fmt::format("colour change (R {:+.1f}, G {:+.1f}, B {:+.1f} levels)", mean[0], mean[1],
                         mean[2]);
      break;
    case ChangeKind::kOpacity:
      what = fmt::format("more {} (alpha {:+.1f} levels)", mean[0] > 0 ? "opaque" : "transparent",
                         mean[0]);
      break;
    case ChangeKind::kAdded:
      what = "content added";
      break;
    case ChangeKind::kRemoved:
      what = "content removed";
      break;
    case ChangeKind::kNoise:
      what = fmt::format("noise (mean |Δ| {:.1f} levels)", mean[0]);
      break;
    case ChangeKind::kOther:
      what = fmt::format("content changed (mean |Δ| {:.1f} levels)", mean[0]);
      break;
  }
  return fmt::format("{}, {}x{} at ({}, {}), {} px", what, width, height, left, top, pixels);
}

std::vector<ChangedRegion> changed_regions(const RgbaImage& expected, const RgbaImage& actual,
                                           const std::vector<std::uint8_t>& ignored,
                                           int max_regions, std::uint64_t max_bytes) {
  const int w = expected.width(), h = expected.height();
  if (w != actual.width() || h != actual.height() || w == 0 || h == 0) return {};
  const std::uint64_t n = std::uint64_t(w) * std::uint64_t(h);
  if (n > UINT32_MAX || n > max_bytes / kAnalysisBytesPerPixel) return {};
  std::vector<std::uint8_t> changed(n, 0);
  for (std::size_t i = 0; i < changed.size(); ++i) {
    if (!ignored.empty() && ignored[i]) continue;
    changed[i] =
        !std::equal(expected.data() + 4 * i, expected.data() + 4 * i + 4, actual.data() + 4 * i);
  }
  std::vector<Component> parts = components(changed, w, h);
  std::ranges::sort(parts, [](const Component& a, const Component& b) {
    return a.pixels.size() > b.pixels.size();
  });
  std::vector<ChangedRegion> out;
  Component scattered;  // small components and those past max_regions: one noise region
  scattered.left = w, scattered.top = h, scattered.right = -1, scattered.bottom = -1;
  const auto is_region = [&](const Component& c, std::size_t k) {
    return static_cast<long long>(c.pixels.size()) >= kSmallRegion && k < std::size_t(max_regions);
  };
  std::size_t regions = 0, scattered_pixels = 0;  // reserved at once: no doubling past the bound
  for (const Component& c : parts) {
    if (is_region(c, regions))
      ++regions;
    else
      scattered_pixels += c.pixels.size();
  }
  scattered.pixels.reserve(scattered_pixels);
  for (Component& c : parts) {
    if (is_region(c, out.size())) {
      out.push_back(classify(c, changed, expected, actual));
      continue;
    }
    scattered.pixels.insert(scattered.pixels.end(), c.pixels.begin(), c.pixels.end());
    std::vector<std::uint32_t>().swap(c.pixels);  // each index held once, not twice
    scattered.left = std::min(scattered.left, c.left),
    scattered.top = std::min(scattered.top, c.top);
    scattered.right = std::max(scattered.right, c.right);
    scattered.bottom = std::max(scattered.bottom, c.bottom);
  }
  if (!scattered.pixels.empty()) {
    ChangedRegion r = classify(scattered, changed, expected, actual);
    // Scattered pixels are noise unless they all moved or changed alike.
    if (r.kind != ChangeKind::kShift && r.kind != ChangeKind::kBrightness &&
        r.kind != ChangeKind::kColour && r.kind != ChangeKind::kOpacity)
      r.kind = ChangeKind::kNoise;
    out.push_back(r);
  }
  return out;
}

nlohmann::json changes_json(const std::vector<ChangedRegion>& regions) {
  nlohmann::json out = nlohmann::json::array();
  for (const ChangedRegion& r : regions) {
    out.push_back({{"kind", change_kind_name(r.kind)},
                   {"text", r.text()},
                   {"left", r.left},
                   {"top", r.top},
                   {"width", r.width},
                   {"height", r.height},
                   {"pixels", r.pixels},
                   {"dx", r.dx},
                   {"dy", r.dy},
                   {"mean", {r.mean[0], r.mean[1], r.mean[2]}}});
  }
  return out;
}

std::vector<ChangedRegion> changes_from_json(const nlohmann::json& j) {
  std::vector<ChangedRegion> out;
  if (!j.is_array()) return out;
  for (const nlohmann::json& e : j) {
    ChangedRegion r;
    const std::string kind = e.value("kind", "");
    for (int k = 0; k <= int(ChangeKind::kOther); ++k) {
      if (change_kind_name(ChangeKind(k)) == kind) r.kind = ChangeKind(k);
    }
    r.left = e.value("left", 0), r.top = e.value("top", 0);
    r.width = e.value("width", 0), r.height = e.value("height", 0);
    r.pixels = e.value("pixels", 0LL), r.dx = e.value("dx", 0), r.dy = e.value("dy", 0);
    if (const auto m = e.find("mean"); m != e.end() && m->is_array() && m->size() == 3) {
      for (int k = 0; k < 3; ++k)
        r.mean[k] = (*m)[std::size_t(k)].is_number() ? (*m)[std::size_t(k)].get<double>() : 0.0;
    }
    out.push_back(r);
  }
  return out;
}

std::string changes_text(const std::vector<ChangedRegion>& regions, std::size_t shown) {
  std::string out;
  for (std::size_t i = 0; i < regions.size() && i < shown; ++i)
    out += (out.empty() ? "" : "; ") + regions[i].text();
  if (regions.size() > shown) out += fmt::format("; and {} more", regions.size() - shown);
  return out;
}

}  // namespace aosuite::comparison
