// SSIM (Wang et al. 2004) as scikit-image 0.19 defines structural_similarity(...,
// gaussian_weights=True, sigma=1.5, use_sample_covariance=False): an 11-tap Gaussian window
// (radius int(3.5 sigma + 0.5) = 5, weights normalised to sum 1) applied separably with
// scipy's 'reflect' border (d c b a | a b c d), population (co)variances, C1 = (K1 L)^2,
// C2 = (K2 L)^2, and the mean of the SSIM map after cropping (window - 1) / 2 = 5 pixels
// from each side; RGB: the mean of the three channels' means. Everything in double.
//
// The one SSIM of the project: reference/error_metrics uses ssim_map() with replicated
// borders and L = 1.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "image/rgba_image.hpp"

namespace aosuite::ssim {

enum class Border {
  reflect,    // scipy.ndimage 'reflect' (scikit-image's default here): d c b a | a b c d
  replicate,  // a a a a | a b c d
};

struct Options {
  double data_range = 255.0;  // L; must be > 0
  double k1 = 0.01, k2 = 0.03;
  double sigma = 1.5, truncate = 3.5;  // window radius int(truncate * sigma + 0.5)
  Border border = Border::reflect;
  // width * height flags (row-major): when given, the mean covers only the pixels whose flag is
  // non-zero (within the crop), e.g. geometry and not sky. Filtering still sees every pixel.
  const std::uint8_t* counted = nullptr;
};

// One channel: element (x, y) at data[y * row_stride + x * pixel_stride].
template <class T>
struct Plane {
  const T* data = nullptr;
  int width = 0, height = 0;
  std::size_t row_stride = 0, pixel_stride = 1;
};

struct SsimResult {
  double mean = 0;  // RGB: mean of channel_means[0..2]; one channel: channel_means[0]
  int channels = 0;
  std::array<double, 3> channel_means{};
};

// The mean SSIM over the map cropped by the window radius on each side, as scikit-image
// returns it. Images with a side shorter than the window (which scikit-image refuses) are
// averaged over the whole map instead. Identical images give exactly 1. Throws
// std::invalid_argument for different sizes or data_range <= 0.
SsimResult compare_rgb(RgbaView a, RgbaView b,
                       const Options& options = {});  // R, G, B; alpha ignored
SsimResult compare(Plane<std::uint8_t> a, Plane<std::uint8_t> b, const Options& options = {});
SsimResult compare(Plane<float> a, Plane<float> b, const Options& options);
// `channels` (1 to 3) interleaved float channels: a and b view channel 0, pixel_stride apart.
SsimResult compare_channels(Plane<float> a, Plane<float> b, int channels, const Options& options);

// The whole SSIM map of one channel, width * height floats (row-major) into `out`.
void ssim_map(Plane<float> a, Plane<float> b, const Options& options, float* out);

}  // namespace aosuite::ssim
