#include "harness/report_images.hpp"

#include <fmt/format.h>
#include <xxhash.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "common/file_io.hpp"
#include "compare/srgb.hpp"
#include "harness/results.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxStops = 24;

// The formats every browser draws in an <img>; any other image gets a preview.
bool browser_shows(const fs::path& file) {
  std::string ext = file.extension().string();
  std::ranges::transform(ext, ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".webp" || ext == ".bmp";
}

// `.s<k>` at the end of a preview's stem: the stops it is darkened by.
std::string stops_suffix(int stops) { return fmt::format(".s{}", stops); }

// Whether `name` is `stem`.<16 hex digits>[.s<k>].png: a preview of the file `stem`, of any
// bytes (without .s<k>: one an earlier aosuite made, clipped at 1, to be removed).
bool is_preview_of(const std::string& name, const std::string& stem) {
  const std::size_t hex = stem.size() + 1;
  if (name.size() < hex + 16 + 4 || !name.starts_with(stem + ".") || !name.ends_with(".png"))
    return false;
  const std::string rest = name.substr(hex + 16, name.size() - hex - 16 - 4);
  return std::all_of(name.begin() + long(hex), name.begin() + long(hex + 16),
                     [](unsigned char c) { return std::isxdigit(c); }) &&
         (rest.empty() || stops_suffix(stops_of_preview(name)) == rest);
}

// Removes the previews of `file` other than `keep`, and their thumbnails: what an earlier
// version of the image left.
void remove_old_previews(const fs::path& file, const std::string& keep) {
  const std::string stem = file.filename().string();
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(file.parent_path(), ec)) {
    const std::string name = e.path().filename().string();
    const std::string shown = name.starts_with("thumb_") ? name.substr(6) : name;
    if (shown != keep && is_preview_of(shown, stem) && fs::is_regular_file(e.symlink_status(ec)))
      fs::remove(e.path(), ec);
  }
}

// `rel`'s preview named `stem`.s<k>.png (any k) that an earlier run made, found in one scan of
// its folder; empty when there is none.
std::string made_preview(const fs::path& dir, const std::string& rel, const std::string& stem) {
  const fs::path folder = fs::path(rel).parent_path();
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir / folder, ec)) {
    const std::string name = e.path().filename().string();
    if (!name.starts_with(stem + ".s") || !name.ends_with(".png")) continue;
    const std::string made = (folder / name).string();
    if (name == stem + stops_suffix(stops_of_preview(name)) + ".png" && inside(dir, made))
      return made;
  }
  return "";
}

unsigned char byte_of(float encoded) {
  return static_cast<unsigned char>(std::lround(std::clamp(encoded, 0.0f, 1.0f) * 255.0f));
}

}  // namespace

bool inside(const fs::path& dir, const std::string& rel) {
  std::error_code ec;
  const fs::path r = fs::path(rel).lexically_normal();
  return !rel.empty() && r.is_relative() && !r.empty() && *r.begin() != ".." &&
         fs::is_regular_file(fs::symlink_status(dir / r, ec));
}

int preview_stops(const Picture& p) {
  if (!p.is_float || p.floats.srgb) return 0;
  // The 99.9th percentile of the finite samples, not their maximum: a few fireflies must not
  // darken the whole picture into the lowest codes; they clip, as on a screen.
  std::vector<float> finite;
  finite.reserve(p.floats.data.size());
  for (float v : p.floats.data)
    if (std::isfinite(v)) finite.push_back(v);
  if (finite.empty()) return 0;
  const auto at = finite.begin() + std::ptrdiff_t(finite.size() * 999 / 1000);
  std::nth_element(finite.begin(), at, finite.end());
  const float highlight = *at;
  int k = 0;
  while (k < kMaxStops && highlight > std::ldexp(1.0f, k)) ++k;
  return k;
}

int stops_of_preview(const std::string& rel) {
  if (!rel.ends_with(".png")) return 0;
  const std::size_t dot = rel.rfind('.', rel.size() - 5);
  if (dot == std::string::npos || rel.compare(dot, 2, ".s") != 0) return 0;
  const std::string digits = rel.substr(dot + 2, rel.size() - 4 - dot - 2);
  if (digits.empty() || digits.size() > 2 ||
      !std::ranges::all_of(digits, [](unsigned char c) { return std::isdigit(c) != 0; }))
    return 0;
  const int k = std::stoi(digits);
  return k <= kMaxStops && stops_suffix(k) == rel.substr(dot, rel.size() - 4 - dot) ? k : 0;
}

RgbaImage display_rgba8(const Picture& p, int stops) {
  if (!p.is_float) return p.rgba;
  const FloatImage& f = p.floats;
  const float gain = std::ldexp(1.0f, -stops);
  RgbaImage out(f.width, f.height);
  for (int y = 0; y < f.height; ++y) {
    const float* in = f.row(y);
    unsigned char* px = out.data() + 4 * std::size_t(y) * std::size_t(f.width);
    for (int x = 0; x < f.width; ++x, px += 4) {
      for (int k = 0; k < 3; ++k) {
        float v =
            in[std::size_t(x) * std::size_t(f.channels) + std::size_t(f.channels == 3 ? k : 0)];
        if (std::isnan(v)) v = 0;  // a NaN sample is black, not whatever a cast makes of it
        v *= gain;
        px[k] = byte_of(f.srgb ? v : linear_to_srgb(v));
      }
      px[3] = 255;
    }
  }
  return out;
}

std::string shown_image(const fs::path& dir, const std::string& rel) {
  if (!inside(dir, rel)) return "";
  if (browser_shows(rel)) return rel;
  const fs::path file = dir / rel;
  try {
    const std::vector<unsigned char> bytes = read_file(file, kMaxFileBytes);
    const std::string stem = fmt::format("{}.{:016x}", file.filename().string(),
                                         XXH3_64bits(bytes.data(), bytes.size()));
    // Named by these bytes: made from them (whatever its stops, which the bytes decide).
    if (const std::string made = made_preview(dir, rel, stem); !made.empty()) return made;
    const Picture picture = decode_picture(bytes, file.string(), kMaxFileBytes);
    const int stops = preview_stops(picture);
    const std::string name = stem + stops_suffix(stops) + ".png";
    const std::string out = (fs::path(rel).parent_path() / name).string();
    write_report_file(file.parent_path() / name,
                      encode_png_rgba8(display_rgba8(picture, stops), 6));
    remove_old_previews(file, name);
    return out;
  } catch (const std::exception&) {
    return "";  // an unreadable image gets no preview; the page links the file and says why
  }
}

constexpr int kThumbW = 160, kThumbH = 120;
RgbaImage ignored_overlay(std::span<const std::uint8_t> ignored, int width, int height) {
  RgbaImage out(width, height);
  const auto at = [&](int x, int y) {
    return ignored[std::size_t(y) * std::size_t(width) + std::size_t(x)] != 0;
  };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      unsigned char* p = out.data() + 4 * (std::size_t(y) * std::size_t(width) + std::size_t(x));
      if (!at(x, y)) {
        std::fill_n(p, 4, 0);
        continue;
      }
      // An edge: an ignored pixel beside a compared one or the frame.
      const bool edge = x == 0 || y == 0 || x == width - 1 || y == height - 1 || !at(x - 1, y) ||
                        !at(x + 1, y) || !at(x, y - 1) || !at(x, y + 1);
      p[0] = 0, p[1] = 120, p[2] = 255, p[3] = edge ? 255 : 96;
    }
  }
  return out;
}

std::string thumbnail(const fs::path& dir, const std::string& rel) {
  if (!inside(dir, rel)) return "";
  const fs::path file = dir / rel;
  try {
    const std::vector<unsigned char> bytes = read_file(file, kMaxFileBytes);
    // A PNG small enough is its own thumbnail; any other image (JPEG, WebP, TIFF, ...) gets a PNG
    // one, which every browser shows.
    const bool is_png_file = is_png(bytes);
    if (is_png_file) {
      const ImageSize size = check_png(bytes, file.string());
      if (size.width <= kThumbW && size.height <= kThumbH) return rel;
    }
    const std::string name = "thumb_" + file.filename().string() + (is_png_file ? "" : ".png");
    const fs::path thumb = file.parent_path() / name;
    std::error_code ec;
    if (fs::exists(thumb, ec) && fs::last_write_time(thumb, ec) >= fs::last_write_time(file, ec)) {
      return fs::path(rel).parent_path().string() + "/" + name;
    }
    const RgbaImage img = is_png_file ? decode_png(bytes, file.string())
                                      : decode_rgba8(bytes, file.string(), kMaxFileBytes);
    const int w = img.width(), h = img.height();
    const int f = std::max((w + kThumbW - 1) / kThumbW, (h + kThumbH - 1) / kThumbH);
    RgbaImage small((w + f - 1) / f, (h + f - 1) / f);
    // Each thumbnail pixel: the rounded mean of the f x f block it covers.
    for (int y = 0; y < small.height(); ++y) {
      for (int x = 0; x < small.width(); ++x) {
        int sum[4] = {0, 0, 0, 0}, count = 0;
        for (int yy = y * f; yy < std::min(h, (y + 1) * f); ++yy) {
          for (int xx = x * f; xx < std::min(w, (x + 1) * f); ++xx) {
            const unsigned char* p = img.view().row(yy) + 4 * xx;
            for (int k = 0; k < 4; ++k) sum[k] += p[k];
            ++count;
          }
        }
        unsigned char* out =
            small.data() + 4 * (std::size_t(y) * std::size_t(small.width()) + std::size_t(x));
        for (int k = 0; k < 4; ++k)
          out[k] = static_cast<unsigned char>((sum[k] + count / 2) / count);
      }
    }
    const std::vector<unsigned char> png = encode_png_rgba8(small, 6);
    write_report_file(thumb, png);
    return fs::path(rel).parent_path().string() + "/" + name;
  } catch (const std::exception&) {
    return "";  // an unreadable image gets no thumbnail; the case still shows why
  }
}

}  // namespace aosuite::harness
