// SSIM in one pass over the rows per thread: each input row is widened to double, padded by
// the border rule, and its five moments (a, b, a^2, b^2, ab) filtered horizontally into a
// ring of 2r + 1 rows; each output row filters the ring vertically and evaluates
// ((2 mu_a mu_b + C1)(2 cov + C2)) / ((mu_a^2 + mu_b^2 + C1)(var_a + var_b + C2)).
#include "compare/ssim.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "compare/parallel_rows.hpp"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define AOSUITE_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define AOSUITE_SIMD_CLONES
#endif

namespace aosuite::ssim {
namespace {

struct Input {
  bool bytes = true;  // std::uint8_t, else float
  const void* a = nullptr;
  const void* b = nullptr;
  int width = 0, height = 0;
  std::size_t row_stride = 0, pixel_stride = 1;
};

int border_index(int i, int n, Border border) {
  if (border == Border::replicate) return std::clamp(i, 0, n - 1);
  const int period = 2 * n;
  int m = i % period;
  if (m < 0) m += period;
  return m < n ? m : period - 1 - m;
}

std::vector<double> gaussian_taps(const Options& o) {
  const int r = static_cast<int>(o.truncate * o.sigma + 0.5);
  std::vector<double> t(std::size_t(2 * r + 1));
  double sum = 0;
  for (int i = -r; i <= r; ++i) {
    const double v = std::exp(-0.5 * double(i) * double(i) / (o.sigma * o.sigma));
    t[std::size_t(i + r)] = v;
    sum += v;
  }
  for (double& v : t) v /= sum;
  return t;
}

void load(const Input& in, const void* base, int y, double* out) {
  const std::size_t off = std::size_t(y) * in.row_stride;
  const std::size_t ps = in.pixel_stride;
  if (in.bytes) {
    const auto* p = static_cast<const std::uint8_t*>(base) + off;
    for (int x = 0; x < in.width; ++x) out[x] = double(p[std::size_t(x) * ps]);
  } else {
    // NaN counts as 0 and +-inf as +-FLT_MAX, so that no NaN or inf comes out.
    constexpr double kMax = 3.4028234663852886e38;
    const auto* p = static_cast<const float*>(base) + off;
    for (int x = 0; x < in.width; ++x) {
      const double v = double(p[std::size_t(x) * ps]);
      out[x] = v != v ? 0.0 : std::clamp(v, -kMax, kMax);
    }
  }
}

// out[x] = sum_k taps[k] * in[x + k], taps symmetric: the centre, then pairs of mirrored
// inputs with their common weight.
AOSUITE_SIMD_CLONES void filter_row(const double* in, const double* taps, int n, double* out,
                                    int w) {
  const int r = n / 2;
  const double* c = in + r;
  const double t0 = taps[r];
  for (int x = 0; x < w; ++x) out[x] = t0 * c[x];
  for (int k = 1; k <= r; ++k) {
    const double t = taps[r + k];
    const double* lo = c - k;
    const double* hi = c + k;
    for (int x = 0; x < w; ++x) out[x] += t * (lo[x] + hi[x]);
  }
}

AOSUITE_SIMD_CLONES void filter_column(const double* const* rows, const double* taps, int n,
                                       double* out, int w) {
  const int r = n / 2;
  const double t0 = taps[r];
  const double* c = rows[r];
  for (int x = 0; x < w; ++x) out[x] = t0 * c[x];
  for (int k = 1; k <= r; ++k) {
    const double t = taps[r + k];
    const double* lo = rows[r - k];
    const double* hi = rows[r + k];
    for (int x = 0; x < w; ++x) out[x] += t * (lo[x] + hi[x]);
  }
}

AOSUITE_SIMD_CLONES void products(const double* a, const double* b, double* aa, double* bb,
                                  double* ab, int n) {
  for (int i = 0; i < n; ++i) aa[i] = a[i] * a[i], bb[i] = b[i] * b[i], ab[i] = a[i] * b[i];
}

// The SSIM of one row from its filtered moments, into `out`.
AOSUITE_SIMD_CLONES void ssim_row(const double* __restrict ua_row, const double* __restrict ub_row,
                                  const double* __restrict aa_row, const double* __restrict bb_row,
                                  const double* __restrict ab_row, double c1, double c2,
                                  double* __restrict out, int w) {
  for (int x = 0; x < w; ++x) {
    const double ua = ua_row[x], ub = ub_row[x];
    const double va = aa_row[x] - ua * ua, vb = bb_row[x] - ub * ub, cov = ab_row[x] - ua * ub;
    const double num = (2 * ua * ub + c1) * (2 * cov + c2);
    const double den = (ua * ua + ub * ub + c1) * (va + vb + c2);
    out[x] = den > 0 ? num / den : 1.0;
  }
}

// Sum of v[x0, x1) in four interleaved partial sums (a fixed order, so results do not depend
// on the machine).
double row_sum(const double* v, int x0, int x1) {
  double s[4] = {0, 0, 0, 0};
  int x = x0;
  for (; x + 4 <= x1; x += 4) s[0] += v[x], s[1] += v[x + 1], s[2] += v[x + 2], s[3] += v[x + 3];
  for (; x < x1; ++x) s[0] += v[x];
  return (s[0] + s[1]) + (s[2] + s[3]);
}

// Sum of the SSIM map over the crop window, for one channel; the map into `out` if given.
double channel_sum(const Input& in, const Options& o, const std::vector<double>& taps, int crop,
                   float* out) {
  const int w = in.width, h = in.height;
  const int r = static_cast<int>(taps.size() / 2), n = 2 * r + 1;
  const double c1 = (o.k1 * o.data_range) * (o.k1 * o.data_range);
  const double c2 = (o.k2 * o.data_range) * (o.k2 * o.data_range);
  const int x0 = crop, x1 = w - crop, cy0 = crop, cy1 = h - crop;
  std::vector<double> band_sums(std::size_t(std::max(h, 1)), 0.0);

  parallel_rows(w, h, [&](int y0, int y1) {
    const int padded = w + 2 * r;
    const auto W = std::size_t(w), P = std::size_t(padded);
    std::vector<double> pad(5 * P), row(W);
    std::vector<double> ring(5 * std::size_t(n) * W), acc(5 * W);
    std::vector<const double*> rows(static_cast<std::size_t>(n), nullptr);
    auto ring_row = [&](int q, int slot) {
      return ring.data() + (std::size_t(q) * std::size_t(n) + std::size_t(slot)) * W;
    };
    auto slot_of = [&](int j) { return (j - y0 + r) % n; };
    auto horizontal = [&](int j) {
      const int src = border_index(j, h, o.border);
      for (int img = 0; img < 2; ++img) {
        load(in, img == 0 ? in.a : in.b, src, row.data());
        double* p = pad.data() + std::size_t(img) * P;
        for (int x = -r; x < w + r; ++x) p[x + r] = row[std::size_t(border_index(x, w, o.border))];
      }
      double* p = pad.data();
      products(p, p + P, p + 2 * P, p + 3 * P, p + 4 * P, padded);
      const int slot = slot_of(j);
      for (int q = 0; q < 5; ++q)
        filter_row(p + std::size_t(q) * P, taps.data(), n, ring_row(q, slot), w);
    };
    for (int j = y0 - r; j < y0 + r; ++j) horizontal(j);
    const double* m[5];
    std::vector<double> s_row(W);
    double sum = 0;
    for (int y = y0; y < y1; ++y) {
      horizontal(y + r);
      for (int q = 0; q < 5; ++q) {
        for (int k = 0; k < n; ++k) rows[std::size_t(k)] = ring_row(q, slot_of(y - r + k));
        filter_column(rows.data(), taps.data(), n, acc.data() + std::size_t(q) * W, w);
        m[q] = acc.data() + std::size_t(q) * W;
      }
      ssim_row(m[0], m[1], m[2], m[3], m[4], c1, c2, s_row.data(), w);
      if (out) {
        float* map_row = out + std::size_t(y) * W;
        for (int x = 0; x < w; ++x) map_row[x] = static_cast<float>(s_row[std::size_t(x)]);
      }
      if (y >= cy0 && y < cy1 && !o.counted) sum += row_sum(s_row.data(), x0, x1);
      if (y >= cy0 && y < cy1 && o.counted) {
        const std::uint8_t* c = o.counted + std::size_t(y) * W;
        for (int x = x0; x < x1; ++x) sum += c[x] ? s_row[std::size_t(x)] : 0.0;
      }
    }
    band_sums[std::size_t(y0)] = sum;
  });
  double total = 0;
  for (double s : band_sums) total += s;
  return total;
}

void check(const Input& a, const Options& o) {
  if (!(o.data_range > 0) || !std::isfinite(o.data_range))
    throw std::invalid_argument("ssim: data_range must be positive");
  if (!(o.sigma > 0) || !(o.truncate >= 0) || o.truncate * o.sigma > 1000)
    throw std::invalid_argument("ssim: sigma must be positive and the window at most 2001 wide");
  if (a.width > 0 && a.height > 0 && (!a.a || !a.b))
    throw std::invalid_argument("ssim: image without data");
}

// Mean over channels of the per-channel cropped mean.
SsimResult run(std::vector<Input> channels, const Options& o) {
  SsimResult r;
  r.channels = static_cast<int>(channels.size());
  if (channels.empty()) return r;
  check(channels[0], o);
  const auto taps = gaussian_taps(o);
  const int radius = static_cast<int>(taps.size() / 2);
  const int w = channels[0].width, h = channels[0].height;
  if (w <= 0 || h <= 0) {
    r.mean = 1.0;
    r.channel_means.fill(1.0);  // nothing differs
    return r;
  }
  // scikit-image crops the window radius; images smaller than the window keep everything.
  const int crop = (w >= 2 * radius + 1 && h >= 2 * radius + 1) ? radius : 0;
  double count = double(w - 2 * crop) * double(h - 2 * crop);
  if (o.counted) {
    count = 0;
    for (int y = crop; y < h - crop; ++y)
      for (int x = crop; x < w - crop; ++x)
        count += o.counted[std::size_t(y) * std::size_t(w) + std::size_t(x)] != 0;
    if (count == 0) {  // nothing counted: nothing differs
      r.mean = 1.0;
      r.channel_means.fill(1.0);
      return r;
    }
  }
  double total = 0;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    r.channel_means[c] = channel_sum(channels[c], o, taps, crop, nullptr) / count;
    total += r.channel_means[c];
  }
  r.mean = total / double(channels.size());
  return r;
}

template <class T>
Input input_of(Plane<T> a, Plane<T> b) {
  if (a.width != b.width || a.height != b.height || a.width < 0 || a.height < 0)
    throw std::invalid_argument("ssim: images differ in size");
  Input in;
  in.bytes = std::is_same_v<T, std::uint8_t>;
  in.a = a.data, in.b = b.data;
  in.width = a.width, in.height = a.height;
  in.row_stride = a.row_stride, in.pixel_stride = a.pixel_stride;
  if (a.row_stride != b.row_stride || a.pixel_stride != b.pixel_stride)
    throw std::invalid_argument("ssim: planes must share their layout");
  return in;
}

}  // namespace

SsimResult compare_rgb(RgbaView a, RgbaView b, const Options& options) {
  std::vector<Input> channels;
  for (int c = 0; c < 3; ++c) {
    const Plane<std::uint8_t> pa{a.data ? a.data + c : nullptr, a.width, a.height,
                                 std::size_t(a.width) * 4, 4};
    const Plane<std::uint8_t> pb{b.data ? b.data + c : nullptr, b.width, b.height,
                                 std::size_t(b.width) * 4, 4};
    channels.push_back(input_of(pa, pb));
  }
  return run(channels, options);
}

SsimResult compare(Plane<std::uint8_t> a, Plane<std::uint8_t> b, const Options& options) {
  return run({input_of(a, b)}, options);
}

SsimResult compare(Plane<float> a, Plane<float> b, const Options& options) {
  return run({input_of(a, b)}, options);
}

SsimResult compare_channels(Plane<float> a, Plane<float> b, int channels, const Options& options) {
  if (channels < 1 || channels > 3) throw std::invalid_argument("ssim: 1 to 3 channels");
  std::vector<Input> inputs;
  for (int c = 0; c < channels; ++c) {
    Plane<float> pa = a, pb = b;
    if (pa.data) pa.data += c;
    if (pb.data) pb.data += c;
    inputs.push_back(input_of(pa, pb));
  }
  return run(inputs, options);
}

void ssim_map(Plane<float> a, Plane<float> b, const Options& options, float* out) {
  const Input in = input_of(a, b);
  check(in, options);
  if (in.width <= 0 || in.height <= 0) return;
  channel_sum(in, options, gaussian_taps(options), 0, out);
}

}  // namespace aosuite::ssim
