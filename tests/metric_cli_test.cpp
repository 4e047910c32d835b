// `aosuite compare --metric` as a user runs it: the differential pairs read back from PNG and
// EXR files through the command (FLIP and SSIM against the reference tools' numbers), 16-bit
// PNGs kept at 16 bits, gates and exit codes, and every bad input answered in one line with
// nothing written.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "compare/metric.hpp"
#include "compare/opencv.hpp"
#include "exr_fixture.hpp"
#include "png_fixture.hpp"
#include "process.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::write_exr;
const fs::path kSource = AOSUITE_SOURCE_DIR;

Outcome compare(const test::TempDir& dir, const std::string& args) {
  return test::run_shell(std::string(AOSUITE_BIN) + " compare " + args, dir.path());
}

// An RGB float EXR whose data window starts at (x0, y0), written with OpenEXR itself (OpenImageIO
// crashes writing windows this far out).
void write_exr_at(const fs::path& path, int w, int h, int x0, int y0,
                  const std::vector<float>& rgb) {
  const Imath::Box2i window({x0, y0}, {x0 + w - 1, y0 + h - 1});
  Imf::Header header(Imath::Box2i({0, 0}, {w - 1, h - 1}), window);
  Imf::FrameBuffer fb;
  for (int c = 0; c < 3; ++c) {
    const char* name = c == 0 ? "R" : c == 1 ? "G" : "B";
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    fb.insert(name, Imf::Slice::Make(Imf::FLOAT, rgb.data() + c, window, 3 * sizeof(float),
                                     3 * sizeof(float) * std::size_t(w)));
  }
  Imf::OutputFile out(path.c_str(), header);
  out.setFrameBuffer(fb);
  out.writePixels(h);
}

void write_png16(const fs::path& path, int w, int h, const std::vector<std::uint16_t>& rgb) {
  OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT16);
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out && out->open(path.string(), spec) &&
              out->write_image(OIIO::TypeDesc::UINT16, rgb.data()) && out->close());
}

nlohmann::json oracle() {
  std::ifstream f(kSource / "tests/data/metric_oracle.json");
  return nlohmann::json::parse(f);
}

// Every oracle pair the command can be asked about as it stands (ACES for HDR: the tool's
// default tone mapper), through files and --batch, one process.
TEST(MetricCli, ReadsThePairsFromFilesAsTheReferenceToolsDo) {
  test::TempDir dir;
  const fs::path pairs = dir / "pairs";
  const Outcome made = test::run_shell(std::string(AOSUITE_ORACLE_INPUTS) + " " + pairs.string() +
                                           " " + (kSource / "tests/data/metric_renders").string(),
                                       dir.path());
  ASSERT_EQ(made.rc, 0) << made.err;
  std::map<std::string, nlohmann::json> expected;
  const nlohmann::json doc = oracle();
  for (const auto& p : doc.at("pairs")) expected[p.at("name").get<std::string>()] = p;
  std::ifstream manifest_file(pairs / "manifest.json");
  const auto manifest = nlohmann::json::parse(manifest_file);
  std::ofstream batch(dir / "batch.jsonl");
  int ldr = 0, hdr = 0;
  for (const auto& p : manifest) {
    const std::string name = p.at("name"), ext = p.at("hdr").get<bool>() ? ".exr" : ".png";
    if (p.at("hdr").get<bool>() && p.at("tone_mapper") != "aces") continue;
    (p.at("hdr").get<bool>() ? hdr : ldr) += 1;
    batch << nlohmann::json{{"id", name},
                            {"a", (pairs / (name + "_a" + ext)).string()},
                            {"b", (pairs / (name + "_b" + ext)).string()}}
                 .dump()
          << "\n";
  }
  batch.close();
  ASSERT_GE(ldr, 100);
  ASSERT_GE(hdr, 20);
  const Outcome r =
      compare(dir, "--batch " + (dir / "batch.jsonl").string() + " --metric flip --metric ssim");
  ASSERT_NE(r.rc, 2) << r.err;  // measured; the pairs differ, so Resemble's gate says 1
  std::istringstream lines(r.out);
  int checked = 0, ssim_checked = 0;
  for (std::string line; std::getline(lines, line);) {
    const auto got = nlohmann::json::parse(line);
    const std::string name = got.at("id");
    SCOPED_TRACE(name);
    ASSERT_TRUE(expected.count(name)) << line;
    // Resemble's comparison always runs on 8-bit pairs (its gate is in force), never on floats.
    const bool is_float = got.at("a").get<std::string>().ends_with(".exr");
    EXPECT_EQ(got.contains("misMatchPercentage"), !is_float) << line;
    const auto& want = expected.at(name).at("flip");
    const auto& flip = got.at("flip");
    EXPECT_NEAR(flip.at("mean").get<double>(), want.at("mean").get<double>(), 2e-6);
    for (const auto& [key, tool_key] :
         std::map<std::string, std::string>{{"weighted_median", "weighted_median"},
                                            {"q1", "first_weighted_quartile"},
                                            {"q3", "third_weighted_quartile"},
                                            {"min", "min"},
                                            {"max", "max"}}) {
      EXPECT_NEAR(flip.at(key).get<double>(), want.at(tool_key).get<double>(), 2e-5) << key;
    }
    if (flip.contains("start_exposure")) {
      EXPECT_NEAR(flip.at("start_exposure").get<double>(), want.at("start_exposure"), 1e-5);
      EXPECT_NEAR(flip.at("stop_exposure").get<double>(), want.at("stop_exposure"), 1e-5);
    }
    if (expected.at(name).contains("ssim_rgb")) {
      EXPECT_NEAR(got.at("ssim").at("mean").get<double>(),
                  expected.at(name).at("ssim_rgb").get<double>(), 1e-6);
      ++ssim_checked;
    }
    ++checked;
  }
  EXPECT_EQ(checked, ldr + hdr);
  EXPECT_GE(ssim_checked, 80);

  // --flip-pooling tool: each pooled value as NVlabs' tool prints it (6 decimals), on every
  // pair, in the JSON and in the line for people.
  const Outcome t = compare(
      dir, "--batch " + (dir / "batch.jsonl").string() + " --metric flip --flip-pooling tool");
  ASSERT_NE(t.rc, 2) << t.err;  // measured; the pairs differ
  const auto printed = [](double v) { return fmt::format("{:.6f}", float(v)); };
  std::istringstream tool_lines(t.out);
  int tool_checked = 0;
  for (std::string line; std::getline(tool_lines, line); ++tool_checked) {
    const auto got = nlohmann::json::parse(line);
    const std::string name = got.at("id");
    SCOPED_TRACE(name);
    const auto& want = expected.at(name).at("flip");
    for (const auto& [key, tool_key] :
         {std::pair{"mean", "mean"}, std::pair{"weighted_median", "weighted_median"},
          std::pair{"q1", "first_weighted_quartile"}, std::pair{"q3", "third_weighted_quartile"}}) {
      EXPECT_EQ(printed(got.at("flip").at(key).get<double>()),
                printed(want.at(tool_key).get<double>()))
          << key;
    }
  }
  EXPECT_EQ(tool_checked, ldr + hdr);
  const std::string name = "render_village_street_sao_with_ao_shift";
  const Outcome one =
      compare(dir, (pairs / (name + "_a.png")).string() + " " +
                       (pairs / (name + "_b.png")).string() + " --metric flip --flip-pooling tool");
  EXPECT_NE(one.out.find("flip: mean " + printed(expected.at(name).at("flip").at("mean")) +
                         " weighted_median "),
            std::string::npos)
      << one.out;
  EXPECT_EQ(compare(dir, "a.png b.png --flip-pooling float").rc, 2);
}

TEST(MetricCli, SixteenBitPngsKeepTheirSixteenBits) {
  test::TempDir dir;
  // One step of 1/65535 in every sample: invisible at 8 bits, an RMSE of exactly that at 16
  // (near 1, where float's own step is largest: 0.4 % of a level, once).
  std::vector<std::uint16_t> a(16 * 16 * 3, 65000), b(16 * 16 * 3, 65001);
  write_png16(dir / "a.png", 16, 16, a);
  write_png16(dir / "b.png", 16, 16, b);
  const Outcome r = compare(dir, (dir / "a.png").string() + " " + (dir / "b.png").string() +
                                     " --metric rmse --metric psnr --json");
  ASSERT_NE(r.rc, 2) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j.at("rmse").at("value").get<double>(), 1.0 / 65535, 1e-18);
  EXPECT_NEAR(j.at("rmse").at("max_abs").get<double>(), 1.0 / 65535, 1e-18);
  EXPECT_NEAR(j.at("psnr").at("db").get<double>(), 20 * std::log10(65535.0), 1e-9);
  // Resemble.js sees what a canvas sees: 8 bits, where these are the same.
  EXPECT_EQ(compare(dir, (dir / "a.png").string() + " " + (dir / "b.png").string()).rc, 0);
}

// The one PSNR (compare/metric.hpp's psnr_db), decided: identical images are +inf, `null` in
// JSON, for the metric and the AO error statistics alike; any difference is exact, uncapped.
TEST(MetricCli, IdenticalImagesHaveAnInfinitePsnrAndNearIdenticalOnesAreNotCapped) {
  EXPECT_EQ(metric::psnr_db(0), HUGE_VAL);
  EXPECT_DOUBLE_EQ(metric::psnr_db(0.01), 20);
  EXPECT_DOUBLE_EQ(metric::psnr_db(1e-13), 130);  // a 100 dB cap would read 100 here
  test::TempDir dir;
  // 512 x 512, one sample one 8-bit level apart: MSE (257 / 65535)^2 / (3 * 512^2), 107.1 dB.
  std::vector<std::uint16_t> a(512 * 512 * 3, 30000), b = a;
  b[7] = 30257;  // 257 / 65535 is one 8-bit level
  write_png16(dir / "a.png", 512, 512, a);
  write_png16(dir / "b.png", 512, 512, b);
  const auto psnr = [&](const char* x, const char* y) {
    const Outcome r =
        compare(dir, (dir / x).string() + " " + (dir / y).string() + " --metric psnr --json");
    EXPECT_NE(r.rc, 2) << r.err;
    return nlohmann::json::parse(r.out).at("psnr").at("db");
  };
  EXPECT_TRUE(psnr("a.png", "a.png").is_null());
  const double mse = std::pow(257.0 / 65535, 2) / (512.0 * 512 * 3);
  EXPECT_NEAR(psnr("a.png", "b.png").get<double>(), 10 * std::log10(1 / mse), 1e-5);  // floats
}

TEST(MetricCli, GatesDecideTheExitStatusAndTheHeatmapIsWritten) {
  test::TempDir dir;
  cv::Mat a(32, 48, CV_8UC4, cv::Scalar(40, 80, 120, 255)), b = a.clone();
  b(cv::Rect(8, 8, 10, 10)).setTo(cv::Scalar(200, 80, 120, 255));
  write_png_rgba8(dir / "a.png", a);
  write_png_rgba8(dir / "b.png", b);
  const std::string ab = (dir / "a.png").string() + " " + (dir / "b.png").string();
  const Outcome measured = compare(dir, ab + " --metric flip --json");
  // No flip gate: flip is measured, not judged; Resemble's gate, always in force, sees the square.
  ASSERT_EQ(measured.rc, 1) << measured.err;
  const double mean = nlohmann::json::parse(measured.out).at("flip").at("mean");
  ASSERT_GT(mean, 0.001);
  const std::string within = " --gate flip.max=" + std::to_string(mean * 1.01);
  // A gate sits beside Resemble's gate; lifting Resemble's takes its name.
  const std::string no_resemble = " --limit resemble=false";
  EXPECT_EQ(compare(dir, ab + within).rc, 1) << "Resemble sees the square";
  EXPECT_EQ(compare(dir, ab + within + no_resemble).rc, 0);
  const Outcome over =
      compare(dir, ab + " --metric flip --gate flip.max_mean=" + std::to_string(mean * 0.99) +
                       " --heatmap " + (dir / "heat.png").string());
  EXPECT_EQ(over.rc, 1);
  EXPECT_NE(over.out.find("flip mean"), std::string::npos) << over.out;
  const cv::Mat heat = read_png_rgba8(dir / "heat.png");
  ASSERT_EQ(heat.size(), a.size());
  EXPECT_NE(heat.at<cv::Vec4b>(12, 12), heat.at<cv::Vec4b>(30, 40)) << "the square shows";
  // --json says what the exit status says, and which gate failed; without gates, no verdict.
  const Outcome json_over =
      compare(dir, ab + " --gate flip.max_mean=" + std::to_string(mean * 0.99) + " --json");
  EXPECT_EQ(json_over.rc, 1);
  const auto verdict = nlohmann::json::parse(json_over.out);
  EXPECT_EQ(verdict.at("verdict"), "different") << json_over.out;
  // Every limit that failed, each named: Resemble's (the square) and the gate.
  ASSERT_EQ(verdict.at("failed_gates").back().get<std::string>().substr(0, 9), "flip mean")
      << json_over.out;
  EXPECT_NE(verdict.at("failed_gates")[0].get<std::string>().find("mismatch"), std::string::npos);
  const auto json_within =
      nlohmann::json::parse(compare(dir, ab + within + no_resemble + " --json").out);
  EXPECT_EQ(json_within.at("verdict"), "same");
  EXPECT_TRUE(json_within.at("failed_gates").empty());
  EXPECT_EQ(nlohmann::json::parse(measured.out).at("verdict"), "different");
  EXPECT_EQ(compare(dir, ab + " --metric ssim --gate ssim.min=0.5" + no_resemble).rc, 0);
  EXPECT_EQ(compare(dir, ab + " --metric ssim --gate ssim.min=0.9999" + no_resemble).rc, 1);
  // With Resemble too: one object, Resemble's keys first, then one key per metric.
  const auto both =
      nlohmann::json::parse(compare(dir, ab + " --metric resemble --metric ssim --json").out);
  EXPECT_TRUE(both.contains("misMatchPercentage") && both.contains("ssim"));
}

TEST(MetricCli, NonFiniteFloatsAreCountedAndFailUnlessAllowed) {
  test::TempDir dir;
  std::vector<float> a(8 * 8, 0.5f), b = a;
  b[9] = std::numeric_limits<float>::quiet_NaN();
  b[20] = std::numeric_limits<float>::infinity();
  write_exr(dir / "a.exr", 8, 8, {"Y"}, a);
  write_exr(dir / "b.exr", 8, 8, {"Y"}, b);
  const std::string ab = (dir / "a.exr").string() + " " + (dir / "b.exr").string();
  const Outcome r = compare(dir, ab + " --metric rmse --metric ssim --json");
  ASSERT_EQ(r.rc, 1) << r.err;  // measured; with no limit, float images must be identical
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("rmse").at("nonfinite"), 2);
  EXPECT_NEAR(j.at("rmse").at("value").get<double>(), 0.5 * std::sqrt(2.0 / 64), 1e-7)
      << "the two bad samples read as 0";
  EXPECT_TRUE(std::isfinite(j.at("ssim").at("mean").get<double>()));
  EXPECT_EQ(compare(dir, ab + " --gate rmse.max=1").rc, 1);
  EXPECT_EQ(compare(dir, ab + " --gate rmse.max=1 --gate rmse.allow_nonfinite=true").rc, 0);
}

// A data window far from (0, 0) reads as the same pixels at the origin would. The window is
// wide and low enough that addressing it from the buffer by pointer arithmetic wrapped below
// address 0 (exr_fuzz under UBSan); a wrong origin would read the wrong samples or none.
TEST(MetricCli, ExrDataWindowsFarFromTheOriginReadTheirOwnPixels) {
  test::TempDir dir;
  const int w = 32768, h = 2;
  std::vector<float> rgb(std::size_t(w) * h * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = float(i % 251) / 251.0f;
  write_exr_at(dir / "origin.exr", w, h, 0, 0, rgb);
  write_exr_at(dir / "far.exr", w, h, 1000000, 1000000000, rgb);
  const auto rmse = [&](const std::string& a, const std::string& b) {
    const Outcome r =
        compare(dir, (dir / a).string() + " " + (dir / b).string() + " --metric rmse --json");
    EXPECT_NE(r.rc, 2) << r.err;
    return nlohmann::json::parse(r.out).at("rmse");
  };
  EXPECT_EQ(rmse("origin.exr", "far.exr").at("max_abs").get<double>(), 0.0);
  rgb[3 * (w + 5) + 1] += 0.5f;  // green of the second row's sixth pixel
  write_exr_at(dir / "far_changed.exr", w, h, -1000000000, 1000000000, rgb);
  const auto changed = rmse("far.exr", "far_changed.exr");
  EXPECT_NEAR(changed.at("max_abs").get<double>(), 0.5, 1e-6);
  EXPECT_NEAR(changed.at("value").get<double>(), std::sqrt(0.25 / double(rgb.size())), 1e-9);
}

// One line naming the file and the problem, exit 2, nothing written.
// OpenEXR allocates an attribute's declared size before reading it: each size is held to the
// bytes left in the file first (exr_fuzz: 35 bytes claiming 1.7 GB), in every part's header.
TEST(MetricCli, ExrAttributeSizesAreHeldToTheFile) {
  test::TempDir dir;
  std::string claims("\x76\x2f\x31\x01\x02\0\0\0capDate\0strifg\0", 23);
  claims += "linexx";  // "line": a size of 1701734764, little-endian
  const std::string bad = (dir.path() / "claims.exr").string();
  std::ofstream(bad) << claims;
  const Outcome refused = compare(dir, bad + " " + bad + " --metric rmse");
  EXPECT_EQ(refused.rc, 2);
  EXPECT_NE(
      refused.err.find("claims.exr: not a readable EXR file (attribute 'capDate' claims 1701734764 "
                       "bytes, more than the 2 left in the file)"),
      std::string::npos)
      << refused.err;
  // A name from the file reaches the message escaped.
  std::string escape("\x76\x2f\x31\x01\x02\0\0\0cap\x1b[2JDate\0strifg\0", 27);
  std::ofstream(dir.path() / "escape.exr") << escape + "linexx";
  const Outcome escaped =
      compare(dir, (dir.path() / "escape.exr").string() + " " + bad + " --metric rmse");
  EXPECT_EQ(escaped.rc, 2);
  EXPECT_NE(escaped.err.find("attribute 'cap\\x1b[2JDate' claims"), std::string::npos)
      << escaped.err;
  EXPECT_EQ(escaped.err.find('\x1b'), std::string::npos);
  // Two parts (OpenEXR wants one display window for all), two headers: the walk goes on
  // past the first header's end into the second.
  OIIO::ImageSpec specs[2] = {OIIO::ImageSpec(4, 4, 1, OIIO::TypeDesc::FLOAT),
                              OIIO::ImageSpec(4, 4, 1, OIIO::TypeDesc::FLOAT)};
  for (int i = 0; i < 2; ++i) {
    specs[i].channelnames = {"Y"};
    specs[i].attribute("oiio:subimagename", i ? "second" : "first");
  }
  const std::string parts = (dir.path() / "parts.exr").string();
  auto out = OIIO::ImageOutput::create(parts);
  const std::vector<float> px(16, 0.5f);
  ASSERT_TRUE(out && out->open(parts, 2, specs) &&
              out->write_image(OIIO::TypeDesc::FLOAT, px.data()) &&
              out->open(parts, specs[1], OIIO::ImageOutput::AppendSubimage) &&
              out->write_image(OIIO::TypeDesc::FLOAT, px.data()) && out->close());
  const Outcome read = compare(dir, parts + " " + parts + " --metric rmse");
  EXPECT_EQ(read.rc, 0) << read.err;
  EXPECT_NE(read.out.find("rmse: value 0"), std::string::npos) << read.out;
}

// Grey is R = G = B at every depth: an 8-bit grey PNG, a 16-bit grey PNG and a grey (Y) EXR
// each measure against an R, G, B image of the same values as 0, and against other values as
// the three-channel images would.
TEST(MetricCli, GreyCountsAsEqualRgbAtEveryDepth) {
  test::TempDir dir;
  auto p = [&](const char* name) { return (dir / name).string(); };
  // A 4x4 PNG of one value per sample: colour type 0 (grey) or 2 (RGB), 8 or 16 bits.
  const auto flat_png = [&](const char* name, int bits, int colour_type, unsigned value) {
    const int samples = 4 * (colour_type == 2 ? 3 : 1);
    test::Bytes row;
    for (int i = 0; i < samples; ++i) {
      if (bits == 16) row.push_back(static_cast<unsigned char>(value >> 8));
      row.push_back(static_cast<unsigned char>(value));
    }
    test::write_bytes(dir / name, test::make_png(4, 4, bits, colour_type, {row, row, row, row}));
  };
  flat_png("g8.png", 8, 0, 100);
  flat_png("c8.png", 8, 2, 100);
  flat_png("d8.png", 8, 2, 151);
  flat_png("g16.png", 16, 0, 25700);
  flat_png("c16.png", 16, 2, 25700);
  flat_png("d16.png", 16, 2, 38807);
  write_exr(dir / "g.exr", 4, 4, {"Y"}, std::vector<float>(16, 0.25f));
  write_exr(dir / "c.exr", 4, 4, {"R", "G", "B"}, std::vector<float>(48, 0.25f));
  write_exr(dir / "d.exr", 4, 4, {"R", "G", "B"}, std::vector<float>(48, 0.45f));
  // A grey file against a colour one is another layout: a failure unless accepted by name
  // (16-bit and float images; 8-bit ones are compared as a canvas holds them, RGBA).
  const std::string kind = " --limit allow_kind_change=true";
  EXPECT_EQ(compare(dir, p("g16.png") + " " + p("c16.png")).rc, 1);
  EXPECT_NE(compare(dir, p("g16.png") + " " + p("c16.png"))
                .out.find("expected is 16-bit grey, actual is 16-bit colour"),
            std::string::npos);
  for (const char* depth : {"8", "16"}) {
    const std::string g = p(fmt::format("g{}.png", depth).c_str());
    for (const char* metric : {"rmse", "ssim", "flip"}) {
      SCOPED_TRACE(fmt::format("{}-bit {}", depth, metric));
      const Outcome same =
          compare(dir, fmt::format("{} {} --metric {} --json{}", g,
                                   p(fmt::format("c{}.png", depth).c_str()), metric, kind));
      ASSERT_EQ(same.rc, 0) << same.err;
    }
    const Outcome diff = compare(dir, fmt::format("{} {} --metric rmse --json{}", g,
                                                  p(fmt::format("d{}.png", depth).c_str()), kind));
    ASSERT_NE(diff.rc, 2) << diff.err;
    EXPECT_NEAR(nlohmann::json::parse(diff.out)["rmse"]["value"].get<double>(), 51.0 / 255, 1e-6);
  }
  const Outcome same = compare(dir, p("g.exr") + " " + p("c.exr") + " --metric rmse --json" + kind);
  ASSERT_NE(same.rc, 2) << same.err;
  EXPECT_EQ(nlohmann::json::parse(same.out)["rmse"]["value"].get<double>(), 0.0);
  const Outcome diff = compare(dir, p("g.exr") + " " + p("d.exr") + " --metric rmse --json" + kind);
  ASSERT_NE(diff.rc, 2) << diff.err;
  EXPECT_NEAR(nlohmann::json::parse(diff.out)["rmse"]["value"].get<double>(), 0.2, 1e-6);
}

// The density gate tells one concentrated defect from the same number of scattered pixels,
// which Resemble's percentage and RMSE cannot: 100 pixels as one 10x10 blot in 512x512 are
// 100 in one 16x16 window; the same 100 on a 50-pixel grid are 1. Rounding noise (one level)
// differs nowhere. 8-bit PNGs and float EXRs alike.
TEST(MetricCli, TheDensityGateCatchesAConcentratedDefect) {
  test::TempDir dir;
  auto p = [&](const char* name) { return (dir / name).string(); };
  constexpr int kSize = 512;
  cv::Mat base(kSize, kSize, CV_8UC4, cv::Scalar(100, 100, 100, 255));
  cv::Mat blot = base.clone(), spread = base.clone(), noise = base.clone();
  blot(cv::Rect(300, 200, 10, 10)).setTo(cv::Scalar(180, 100, 100, 255));
  for (int y = 0; y < 500; y += 50)
    for (int x = 0; x < 500; x += 50) spread.at<cv::Vec4b>(y, x) = {180, 100, 100, 255};
  noise(cv::Rect(0, 0, 64, 64)).setTo(cv::Scalar(101, 99, 100, 255));
  write_png_rgba8(dir / "base.png", base);
  write_png_rgba8(dir / "blot.png", blot);
  write_png_rgba8(dir / "spread.png", spread);
  write_png_rgba8(dir / "noise.png", noise);
  const auto density = [&](const std::string& a, const std::string& b) {
    const Outcome r =
        compare(dir, a + " " + b + " --gate density.max=20 --limit resemble=false --json");
    const auto j = nlohmann::json::parse(r.out);
    return std::pair{r.rc, j["density"]["count"].get<double>()};
  };
  EXPECT_EQ(density(p("base.png"), p("blot.png")), std::pair(1, 100.0));
  EXPECT_EQ(density(p("base.png"), p("spread.png")), std::pair(0, 1.0));
  EXPECT_EQ(density(p("base.png"), p("noise.png")), std::pair(0, 0.0));
  // The same two pictures as linear floats: the blot's 80/255 is a difference, 1/255 is not.
  std::vector<float> flat(std::size_t(kSize) * kSize * 3, 0.4f), blotted = flat;
  for (int y = 200; y < 210; ++y)
    for (int x = 300; x < 310; ++x) blotted[(std::size_t(y) * kSize + std::size_t(x)) * 3] = 0.72f;
  write_exr(dir / "base.exr", kSize, kSize, {"R", "G", "B"}, flat);
  write_exr(dir / "blot.exr", kSize, kSize, {"R", "G", "B"}, blotted);
  EXPECT_EQ(density(p("base.exr"), p("blot.exr")), std::pair(1, 100.0));
}

TEST(MetricCli, BadInputIsOneLineAndWritesNothing) {
  test::TempDir dir;
  write_png_rgba8(dir / "small.png", cv::Mat(4, 4, CV_8UC4, cv::Scalar::all(9)));
  write_png_rgba8(dir / "wide.png", cv::Mat(4, 6, CV_8UC4, cv::Scalar::all(9)));
  write_exr(dir / "grey.exr", 4, 4, {"Y"}, std::vector<float>(16, 0.25f));
  write_exr(dir / "rgb.exr", 4, 4, {"R", "G", "B"}, std::vector<float>(48, 0.25f));
  write_exr(dir / "depth.exr", 4, 4, {"Z"}, std::vector<float>(16, 1.0f));
  std::ofstream(dir / "cut.exr") << std::string("\x76\x2f\x31\x01", 4) << "garbage";
  const fs::path heat = dir / "heat.png";
  auto p = [&](const char* name) { return (dir / name).string(); };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {p("depth.exr") + " " + p("grey.exr") + " --metric rmse",
       "depth.exr: EXR has no R, G, B or Y channel (it has: Z)"},
      {p("cut.exr") + " " + p("grey.exr") + " --metric rmse", "cut.exr: "},
      {p("small.png") + " " + p("small.png") + " --metric nope", "unknown metric 'nope'"},
      {p("small.png") + " " + p("small.png") + " --gate flip.max_nope=1", "flip has no gate"},
      {p("small.png") + " " + p("small.png") + " --gate flip.max=inf", "not a finite number"},
      {p("small.png") + " " + p("small.png") + " --gate flip", "is not METRIC.KEY=VALUE"},
  };
  for (const auto& [args, message] : cases) {
    SCOPED_TRACE(args);
    const Outcome r = compare(dir, args + " --heatmap " + heat.string());
    EXPECT_EQ(r.rc, 2);
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(heat));
  }
  // Another size or kind is a verdict, not bad input: different, saying why, and no heat map.
  const std::vector<std::pair<std::string, std::string>> verdicts = {
      {p("small.png") + " " + p("wide.png") + " --metric flip", "expected is 4x4, actual is 6x4"},
      {p("grey.exr") + " " + p("small.png") + " --metric ssim",
       "expected is float grey, actual is 8-bit"},
  };
  for (const auto& [args, message] : verdicts) {
    SCOPED_TRACE(args);
    const Outcome r = compare(dir, args + " --heatmap " + heat.string());
    EXPECT_EQ(r.rc, 1) << r.err;
    EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(heat));
  }
}

TEST(MetricCli, OutputsAreWrittenAllOrNoneAndAKindChangeStaysAVerdict) {
  test::TempDir dir;
  write_png_rgba8(dir / "a.png", cv::Mat(4, 4, CV_8UC4, cv::Scalar::all(9)));
  write_png_rgba8(dir / "b.png", cv::Mat(4, 4, CV_8UC4, cv::Scalar::all(90)));
  const std::vector<unsigned char> row(8, 0x40);  // 16-bit grey, 4 pixels
  const std::vector<unsigned char> g16 = test::make_png(4, 4, 16, 0, {row, row, row, row});
  test::write_bytes(dir / "g16.png", g16);
  test::write_bytes(dir / "cut16.png",
                    std::vector<unsigned char>(g16.begin(), g16.begin() + long(g16.size()) - 20));
  auto p = [&](const char* name) { return (dir / name).string(); };
  const fs::path diff = dir / "diff.png";
  // The heat map cannot be written: the diff, which could, is not left behind either.
  Outcome r = compare(dir, p("a.png") + " " + p("b.png") + " --metric flip --diff " +
                               diff.string() + " --heatmap " + (dir / "no" / "h.png").string());
  EXPECT_EQ(r.rc, 2) << r.out;
  EXPECT_FALSE(fs::exists(diff));
  for (const fs::directory_entry& e : fs::directory_iterator(dir.path()))
    EXPECT_FALSE(e.path().filename().string().starts_with(".")) << "left: " << e.path();
  // Asking for a diff does not turn another bit depth into an error: the same verdict and
  // words as without it, and a note that no diff was written.
  for (const std::string& extra : {std::string(), " --diff " + diff.string()}) {
    SCOPED_TRACE(extra);
    r = compare(dir, p("a.png") + " " + p("g16.png") + extra);
    EXPECT_EQ(r.rc, 1) << r.err;
    EXPECT_NE(r.out.find("expected is 8-bit, actual is 16-bit grey"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(diff));
  }
  // A 16-bit PNG cut short is bad input even where its header alone says another kind.
  r = compare(dir, p("cut16.png") + " " + p("a.png"));
  EXPECT_EQ(r.rc, 2) << r.out;
  EXPECT_NE(r.err.find("cut16.png: "), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
}  // namespace aosuite
