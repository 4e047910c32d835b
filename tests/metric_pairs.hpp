// The image pairs of the FLIP and SSIM differential tests, generated deterministically
// (splitmix64; no <random> distributions, whose output is implementation-defined): LDR RGBA8
// pairs (noise, shifts, banding, blur, brightness, channel swaps, identical, translucent
// alpha; plus small AO renders committed in tests/data/metric_renders/) and HDR RGB float pairs
// over several exposure ranges and three tone mappers; sizes from 1x1 to 160x90, odd ones
// included. tests/oracles/metric_oracle_inputs.cpp writes them to files for the reference
// tools; tests/metric_oracle_test.cpp regenerates them in-process.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "compare/opencv.hpp"

namespace aosuite::test {

struct MetricPair {
  std::string name;
  bool hdr = false;
  std::string tone_mapper = "aces";  // HDR only
  cv::Mat a, b;                      // LDR: CV_8UC4 RGBA; HDR: CV_32FC3 linear RGB
};

class SplitMix {
 public:
  explicit SplitMix(std::uint64_t seed) : s_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (s_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }  // [0, 1)
  int below(int n) { return static_cast<int>(next() % std::uint64_t(n)); }

 private:
  std::uint64_t s_;
};

// A smooth-ish base picture in [0, 1]^3: gradients, a few discs and bars, a little noise.
inline void base_picture(SplitMix& rng, int w, int h, std::vector<float>& rgb) {
  rgb.assign(std::size_t(w) * std::size_t(h) * 3, 0.0f);
  const double gx[3] = {rng.uniform(), rng.uniform(), rng.uniform()};
  const double gy[3] = {rng.uniform(), rng.uniform(), rng.uniform()};
  const double off[3] = {rng.uniform() * 0.5, rng.uniform() * 0.5, rng.uniform() * 0.5};
  struct Disc {
    double cx, cy, r, c[3];
  };
  std::vector<Disc> discs(std::size_t(1 + rng.below(4)));
  for (auto& d : discs) {
    d = {rng.uniform() * w,
         rng.uniform() * h,
         (0.1 + 0.4 * rng.uniform()) * std::max(w, h),
         {rng.uniform(), rng.uniform(), rng.uniform()}};
  }
  const double noise = rng.uniform() * 0.1;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double u = (x + 0.5) / w, v = (y + 0.5) / h;
      float* p = &rgb[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3];
      for (int c = 0; c < 3; ++c) {
        double val = off[c] + 0.5 * (gx[c] * u + gy[c] * v);
        for (const auto& d : discs) {
          const double dx = x - d.cx, dy = y - d.cy;
          if (dx * dx + dy * dy < d.r * d.r) val = 0.7 * d.c[c] + 0.3 * val;
        }
        if (((x / 3) + (y / 5)) % 7 == 0) val *= 0.6;  // thin bars: edges for the features
        val += noise * (rng.uniform() - 0.5);
        p[c] = static_cast<float>(std::clamp(val, 0.0, 1.0));
      }
    }
  }
}

inline cv::Mat to_rgba8(const std::vector<float>& rgb, int w, int h, SplitMix* alpha_rng) {
  cv::Mat m(h, w, CV_8UC4);
  for (int y = 0; y < h; ++y) {
    auto* p = m.ptr<unsigned char>(y);
    for (int x = 0; x < w; ++x) {
      const float* s = &rgb[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3];
      for (int c = 0; c < 3; ++c)
        p[4 * x + c] = static_cast<unsigned char>(std::lround(s[c] * 255.0f));
      p[4 * x + 3] = alpha_rng ? static_cast<unsigned char>(alpha_rng->below(256)) : 255;
    }
  }
  return m;
}

// The LDR modifications of b (from a, in place), by index.
inline const char* const kLdrEdits[] = {"noise", "shift", "banding", "blur",      "bright",
                                        "swap",  "salt",  "same",    "noise_big", "alpha"};

inline void edit_ldr(int edit, SplitMix& rng, cv::Mat& b) {
  const int w = b.cols, h = b.rows;
  const cv::Mat a = b.clone();
  auto px = [&](const cv::Mat& m, int x, int y) {
    return m.ptr<unsigned char>(std::clamp(y, 0, h - 1)) + 4 * std::clamp(x, 0, w - 1);
  };
  const int amp = 2 + rng.below(12);
  const int sx = rng.below(3), sy = rng.below(3) - 1, levels = 4 + rng.below(12);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      unsigned char* q = b.ptr<unsigned char>(y) + 4 * x;
      const unsigned char* p = px(a, x, y);
      for (int c = 0; c < 3; ++c) {
        int v = p[c];
        switch (edit) {
          case 0:
            v += rng.below(2 * amp + 1) - amp;
            break;
          case 1:
            v = px(a, x - sx, y - sy)[c];
            break;
          case 2:
            v = (v * levels / 256) * 255 / std::max(levels - 1, 1);
            break;
          case 3:
            v = (px(a, x - 1, y)[c] + 2 * v + px(a, x + 1, y)[c] + px(a, x, y - 1)[c] +
                 px(a, x, y + 1)[c] + 3) /
                6;
            break;
          case 4:
            v = v * (100 + amp * 3) / 100 + amp;
            break;
          case 5:
            v = p[(c + 1) % 3];
            break;
          case 6:
            if (rng.below(20) == 0) v = rng.below(256);
            break;
          case 7:
            break;
          case 8:
            v += rng.below(161) - 80;
            break;
          case 9:
            v += rng.below(7) - 3;
            break;
          default:
            break;
        }
        q[c] = static_cast<unsigned char>(std::clamp(v, 0, 255));
      }
      if (edit == 9) q[3] = static_cast<unsigned char>(rng.below(256));
    }
  }
}

inline void edit_hdr(int edit, SplitMix& rng, cv::Mat& b) {
  const cv::Mat a = b.clone();
  const int w = b.cols, h = b.rows;
  const float gain = static_cast<float>(std::exp2(rng.uniform() * 2 - 1));
  const int sx = 1 + rng.below(2);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float* q = b.ptr<float>(y) + 3 * x;
      const float* p = a.ptr<float>(y) + 3 * x;
      for (int c = 0; c < 3; ++c) {
        float v = p[c];
        switch (edit) {
          case 0:
            v *= static_cast<float>(1.0 + 0.2 * (rng.uniform() - 0.5));
            break;
          case 1:
            v = a.ptr<float>(y)[3 * std::clamp(x - sx, 0, w - 1) + c];
            break;
          case 2:
            v *= gain;
            break;
          case 3:
            v = std::exp2(std::round(std::log2(std::max(v, 1e-30f)) * 2) / 2);
            break;
          case 4:
            break;
          case 5:
            if (rng.below(10) == 0) v = v * 8 + 0.5f;
            break;
          default:
            break;
        }
        q[c] = v;
      }
    }
  }
}

inline const char* const kHdrEdits[] = {"noise", "shift", "gain", "banding", "same", "fireflies"};

// The benchmarks' pair at any size (bench/metric_bench.cpp; metric_oracle_inputs --bench
// writes it for timing the reference tool on the same images): the base picture, and a copy
// with noise (LDR) or multiplicative noise (HDR over 2^-6..2^6).
inline MetricPair bench_pair(int w, int h, bool hdr) {
  SplitMix rng(7);
  std::vector<float> rgb;
  base_picture(rng, w, h, rgb);
  MetricPair p;
  p.hdr = hdr;
  p.name = std::string(hdr ? "hdr_" : "ldr_") + std::to_string(w) + "x" + std::to_string(h);
  if (!hdr) {
    p.a = to_rgba8(rgb, w, h, nullptr);
    p.b = p.a.clone();
    edit_ldr(0, rng, p.b);
    return p;
  }
  p.a = cv::Mat(h, w, CV_32FC3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w * 3; ++x)
      p.a.ptr<float>(y)[x] = static_cast<float>(
          std::exp2(-6.0 + 12.0 * rgb[std::size_t(y) * std::size_t(w) * 3 + std::size_t(x)]));
  p.b = p.a.clone();
  edit_hdr(0, rng, p.b);
  return p;
}

inline std::vector<MetricPair> metric_pairs(const std::filesystem::path& renders_dir = {}) {
  std::vector<MetricPair> pairs;
  const int sizes[][2] = {{1, 1},  {1, 7},   {7, 1},   {2, 2},   {3, 5},   {11, 11},  {12, 13},
                          {16, 9}, {31, 17}, {33, 40}, {64, 48}, {97, 61}, {128, 72}, {160, 90}};
  SplitMix rng(20240607);
  std::vector<float> rgb;
  int index = 0;
  // LDR: every size with every edit, then a few more at the larger sizes.
  for (const auto& s : sizes) {
    for (int edit = 0; edit < 10; ++edit) {
      const int w = s[0], h = s[1];
      base_picture(rng, w, h, rgb);
      MetricPair p;
      p.name = "ldr_" + std::to_string(index++) + "_" + std::to_string(w) + "x" +
               std::to_string(h) + "_" + kLdrEdits[edit];
      p.a = to_rgba8(rgb, w, h, edit == 9 ? &rng : nullptr);
      p.b = p.a.clone();
      edit_ldr(edit, rng, p.b);
      pairs.push_back(std::move(p));
    }
  }
  // HDR: exposure ranges (log2 of the darkest and brightest values) and tone mappers.
  const double ranges[][2] = {{-4, 4}, {-10, 10}, {-2, 0}, {0, 12}, {-14, -6}, {-1, 3}};
  const char* tones[] = {"aces", "aces", "aces", "hable", "reinhard"};
  int hdr_index = 0;
  for (const auto& s : sizes) {
    for (int edit = 0; edit < 6; ++edit) {
      const int w = s[0], h = s[1];
      base_picture(rng, w, h, rgb);
      const auto& r = ranges[hdr_index % 6];
      MetricPair p;
      p.hdr = true;
      p.tone_mapper = tones[hdr_index % 5];
      p.name = "hdr_" + std::to_string(hdr_index++) + "_" + std::to_string(w) + "x" +
               std::to_string(h) + "_" + kHdrEdits[edit] + "_" + p.tone_mapper;
      p.a = cv::Mat(h, w, CV_32FC3);
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w * 3; ++x) {
          const float v = rgb[std::size_t(y) * std::size_t(w) * 3 + std::size_t(x)];
          p.a.ptr<float>(y)[x] = static_cast<float>(std::exp2(r[0] + (r[1] - r[0]) * v));
        }
      }
      // Some black pixels (fewer than half, so the median stays positive).
      if (edit == 5 && w * h > 4)
        p.a.ptr<float>(0)[0] = p.a.ptr<float>(0)[1] = p.a.ptr<float>(0)[2] = 0;
      p.b = p.a.clone();
      edit_hdr(edit, rng, p.b);
      pairs.push_back(std::move(p));
    }
  }
  // Renders: each committed render against the next (same scene, another technique), and
  // against itself shifted by one pixel.
  if (!renders_dir.empty() && std::filesystem::is_directory(renders_dir)) {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(renders_dir))
      if (e.path().extension() == ".png") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (std::size_t i = 0; i < files.size(); ++i) {
      const cv::Mat a = read_png_rgba8(files[i]);
      const cv::Mat b = read_png_rgba8(files[(i + 1) % files.size()]);
      MetricPair p;
      p.name = "render_" + files[i].stem().string();
      p.a = a;
      if (b.size() == a.size()) {
        p.b = b;
      } else {
        p.b = a.clone();
        edit_ldr(1, rng, p.b);
      }
      pairs.push_back(p);
      MetricPair q;
      q.name = p.name + "_shift";
      q.a = a;
      q.b = a.clone();
      edit_ldr(1, rng, q.b);
      pairs.push_back(std::move(q));
    }
  }
  return pairs;
}

}  // namespace aosuite::test
