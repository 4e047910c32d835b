// FLIP and SSIM against the numbers their reference implementations produced on the same
// pairs (tests/data/metric_oracle.json, written by tests/oracles/metric_oracle.py from
// NVlabs/flip v1.6 and scikit-image 0.19): FLIP mean within 2e-6 and pooled values within
// 2e-5, and with the tool's arithmetic (`--flip-pooling tool`) its floats to the bit; SSIM
// within 1e-6. The
// pairs are regenerated here (tests/metric_pairs.hpp). AOSUITE_METRIC_ORACLE overrides the JSON
// (the oracle-live test points it at fresh numbers).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <tuple>

#include "compare/metric.hpp"
#include "compare/metrics_cv.hpp"
#include "tests/metric_pairs.hpp"

namespace aosuite {
namespace {

const std::filesystem::path kSource = AOSUITE_SOURCE_DIR;

nlohmann::json oracle() {
  const char* env = std::getenv("AOSUITE_METRIC_ORACLE");
  const std::filesystem::path path = env ? env : kSource / "tests/data/metric_oracle.json";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  return nlohmann::json::parse(in);
}

flip::ToneMapper tone_of(const std::string& s) {
  return s == "hable" ? flip::ToneMapper::hable
                      : (s == "reinhard" ? flip::ToneMapper::reinhard : flip::ToneMapper::aces);
}

struct Deviation {
  double value = 0;
  std::string where;
  void update(double d, const std::string& name) {
    if (d > value) value = d, where = name;
  }
};

TEST(MetricOracle, FlipAndSsimMatchTheReferenceImplementations) {
  const auto doc = oracle();
  std::map<std::string, nlohmann::json> expected;
  for (const auto& p : doc.at("pairs")) expected[p.at("name").get<std::string>()] = p;
  const auto pairs = test::metric_pairs(kSource / "tests/data/metric_renders");
  ASSERT_GE(pairs.size(), 200u);
  ASSERT_EQ(pairs.size(), expected.size()) << "regenerate tests/data/metric_oracle.json";

  Deviation mean_dev, tool_mean_dev, pooled_dev, ssim_dev;
  int flip_checked = 0, ssim_checked = 0, tool_printed = 0, exact_printed = 0, printed_values = 0;
  for (const auto& p : pairs) {
    SCOPED_TRACE(p.name);
    ASSERT_TRUE(expected.count(p.name)) << "no expected values for " << p.name;
    const auto& e = expected[p.name];
    flip::Options o;
    o.tone_mapper = tone_of(p.tone_mapper);
    const flip::FlipResult r = flip::compare(p.a, p.b, p.hdr, o);
    const auto& f = e.at("flip");
    ASSERT_EQ(r.error_map.size(), std::size_t(p.a.cols) * std::size_t(p.a.rows));
    for (float v : r.error_map) ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << v;
    const double dm = std::abs(r.mean - f.at("mean").get<double>());
    EXPECT_LE(dm, 2e-6) << "mean " << r.mean;
    mean_dev.update(dm, p.name);
    const std::pair<const char*, double> pooled[] = {
        {"weighted_median", r.weighted_median},
        {"first_weighted_quartile", r.first_weighted_quartile},
        {"third_weighted_quartile", r.third_weighted_quartile},
        {"min", r.min},
        {"max", r.max}};
    for (const auto& [key, got] : pooled) {
      const double d = std::abs(got - f.at(key).get<double>());
      EXPECT_LE(d, 2e-5) << key << " " << got << " vs " << f.at(key).get<double>();
      pooled_dev.update(d, p.name + " " + key);
    }
    if (p.hdr) {
      EXPECT_NEAR(r.start_exposure, f.at("start_exposure").get<double>(), 1e-5);
      EXPECT_NEAR(r.stop_exposure, f.at("stop_exposure").get<double>(), 1e-5);
      EXPECT_EQ(r.num_exposures, f.at("num_exposures").get<int>());
    }
    ++flip_checked;
    // The tool's arithmetic (`--flip-pooling tool`): every pooled value the tool's float to the
    // bit (the oracle holds them with 9 significant digits, which name one float each; checked
    // against the tool's printed CSV by tests/oracles/metric_oracle.py --flip-tool), so printed
    // with its 6 decimals they are its output. Exact pooling prints the same less often.
    flip::Options tool_like = o;
    tool_like.tool_arithmetic = true;
    const auto t = flip::compare(p.a, p.b, p.hdr, tool_like);
    tool_mean_dev.update(std::abs(t.mean - f.at("mean").get<double>()), p.name);
    const auto printed = [](double v) { return fmt::format("{:.6f}", float(v)); };
    for (const auto& [key, tool, exact] :
         {std::tuple{"mean", float(t.mean), float(r.mean)},
          std::tuple{"weighted_median", t.weighted_median, r.weighted_median},
          std::tuple{"first_weighted_quartile", t.first_weighted_quartile,
                     r.first_weighted_quartile},
          std::tuple{"third_weighted_quartile", t.third_weighted_quartile,
                     r.third_weighted_quartile},
          std::tuple{"min", t.min, r.min}}) {
      EXPECT_EQ(tool, f.at(key).get<float>()) << key;
      const std::string want = printed(f.at(key).get<double>());
      tool_printed += printed(tool) == want, exact_printed += printed(exact) == want;
      ++printed_values;
    }
    EXPECT_EQ(tool_printed, printed_values);

    auto check_ssim = [&](const char* key, double got) {
      if (!e.contains(key)) return;
      const double d = std::abs(got - e.at(key).get<double>());
      EXPECT_LE(d, 1e-6) << key << " " << got << " vs " << e.at(key).get<double>();
      ssim_dev.update(d, p.name + " " + key);
      ++ssim_checked;
    };
    if (p.hdr) {
      if (e.contains("ssim_float")) {
        cv::Mat fa(p.a.rows, p.a.cols, CV_32F), fb(p.a.rows, p.a.cols, CV_32F);
        for (int y = 0; y < p.a.rows; ++y) {
          for (int x = 0; x < p.a.cols; ++x) {
            const float va = p.a.ptr<float>(y)[3 * x + 1], vb = p.b.ptr<float>(y)[3 * x + 1];
            fa.at<float>(y, x) = va / (1.0f + va);
            fb.at<float>(y, x) = vb / (1.0f + vb);
          }
        }
        ssim::Options so;
        so.data_range = 1.0;
        check_ssim("ssim_float", ssim::compare(fa, fb, so).mean);
      }
    } else {
      check_ssim("ssim_rgb", ssim::compare(p.a, p.b).mean);
      const ssim::Plane<std::uint8_t> ga{p.a.ptr<std::uint8_t>(), p.a.cols, p.a.rows, p.a.step1(),
                                         4};
      const ssim::Plane<std::uint8_t> gb{p.b.ptr<std::uint8_t>(), p.b.cols, p.b.rows, p.b.step1(),
                                         4};
      check_ssim("ssim_gray8", ssim::compare(ga, gb).mean);
    }
  }
  EXPECT_GT(tool_printed, exact_printed);
  std::printf(
      "FLIP: %d pairs, max |mean - tool| %.3g (%s), with tool_arithmetic %.3g (%s), max "
      "|pooled - tool| %.3g (%s); printed as the tool prints (6 decimals), %d of %d values "
      "equal with tool_arithmetic, %d with exact pooling\n"
      "SSIM: %d values, max |ssim - skimage| %.3g (%s)\n",
      flip_checked, mean_dev.value, mean_dev.where.c_str(), tool_mean_dev.value,
      tool_mean_dev.where.c_str(), pooled_dev.value, pooled_dev.where.c_str(), tool_printed,
      printed_values, exact_printed, ssim_checked, ssim_dev.value, ssim_dev.where.c_str());
}

// Properties that need no oracle.
TEST(Flip, IdenticalImagesGiveZeroAndMapsAreFinite) {
  const auto pairs = test::metric_pairs();
  for (const auto& p : pairs) {
    const auto r = flip::compare(p.a, p.a, p.hdr);
    EXPECT_EQ(r.mean, 0.0) << p.name;
    EXPECT_EQ(r.max, 0.0f) << p.name;
  }
}

// CIE L*a*b*'s f(t) turns from a cube root into a line at t = (6/29)^3, the two joining in value
// and slope: two flat greys 1 % apart in linear luminance differ little in FLIP's colour error
// wherever they lie, near that joint and near (6/29)^2 included. A direct check of the curve,
// beside the oracle's pairs (a joint moved to (6/29)^2 fails both).
TEST(Flip, NearbyDarkGreysDifferLittleWhereverLabTurnsLinear) {
  constexpr double kDelta = 6.0 / 29.0;
  for (const double v : {0.002, kDelta * kDelta * kDelta / 1.005, kDelta * kDelta * kDelta, 0.02,
                         kDelta * kDelta / 1.005, kDelta * kDelta, 0.1, 0.5}) {
    const cv::Mat a(8, 8, CV_32FC3, cv::Scalar::all(v)),
        b(8, 8, CV_32FC3, cv::Scalar::all(v * 1.01));
    const double mean = flip::compare(a, b, false).mean;
    EXPECT_LT(mean, 0.05) << "linear grey " << v << " against 1 % brighter";
    EXPECT_GT(mean, 0.0) << v;
  }
}

TEST(Flip, DegenerateHdrInputsStayFinite) {
  cv::Mat black(5, 4, CV_32FC3, cv::Scalar::all(0)), odd = black.clone();
  odd.at<cv::Vec3f>(1, 1) = {std::nanf(""), INFINITY, -INFINITY};
  odd.at<cv::Vec3f>(2, 2) = {1e30f, 1e-30f, -5.0f};
  for (const auto& [a, b] : {std::pair{black, odd}, std::pair{odd, black}, std::pair{odd, odd}}) {
    const auto r = flip::compare(a, b, true);
    EXPECT_TRUE(std::isfinite(r.mean));
    EXPECT_TRUE(std::isfinite(r.start_exposure) && std::isfinite(r.stop_exposure));
    for (float v : r.error_map) EXPECT_TRUE(v >= 0.0f && v <= 1.0f);
  }
  EXPECT_THROW(flip::compare(black, cv::Mat(4, 5, CV_32FC3), true), std::invalid_argument);
}

TEST(Flip, ErrorMapImages) {
  flip::FlipResult r;
  r.width = 3, r.height = 1, r.error_map = {0.0f, 0.5f, 1.0f};
  const auto magma = flip::error_map_image(r);
  EXPECT_EQ(magma.data()[0], 0);
  EXPECT_EQ(magma.data()[2], 4);
  EXPECT_EQ(magma.data()[8], 252);
  EXPECT_EQ(magma.data()[10], 191);
  const auto grey = flip::error_map_image(r, flip::ErrorMapStyle::grey);
  EXPECT_EQ(grey.data()[4], 128);
  EXPECT_EQ(grey.data()[11], 255);
}

// The heat map is one metric's map, chosen in the registry (compare, check and the report ask
// it, none names a metric): exactly one registered metric draws it, FLIP.
TEST(MetricRegistry, ExactlyOneMetricDrawsTheHeatMap) {
  int drawing = 0;
  for (const metric::Metric* m : metric::all()) drawing += m->heatmap;
  EXPECT_EQ(drawing, 1);
  EXPECT_EQ(metric::heatmap_metric().name, "flip");
}

TEST(Ssim, SmallAndDegenerateInputs) {
  cv::Mat a(3, 2, CV_8UC4, cv::Scalar(10, 20, 30, 255)), b(3, 2, CV_8UC4, cv::Scalar(200, 0, 5, 0));
  EXPECT_EQ(ssim::compare(a, a).mean, 1.0);
  const double s = ssim::compare(a, b).mean;
  EXPECT_TRUE(std::isfinite(s) && s < 1.0);
  cv::Mat f(12, 12, CV_32F, cv::Scalar(0.5)), g = f.clone();
  g.at<float>(3, 3) = std::nanf("");
  g.at<float>(4, 4) = INFINITY;
  ssim::Options o;
  o.data_range = 1;
  EXPECT_TRUE(std::isfinite(ssim::compare(f, g, o).mean));
  o.data_range = 0;
  EXPECT_THROW(ssim::compare(f, g, o), std::invalid_argument);
}

}  // namespace
}  // namespace aosuite
