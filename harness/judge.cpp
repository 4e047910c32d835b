#include "harness/judge.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <stdexcept>

#include "common/content_hash.hpp"
#include "compare/verdict.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"
#include "image/png_layout.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

std::string_view status_name(Status s) {
  switch (s) {
    case Status::kPass:
      return "PASS";
    case Status::kFail:
      return "FAIL";
    case Status::kNew:
      return "NEW";
    case Status::kError:
      return "ERROR";
    case Status::kFlaky:
      return "FLAKY";
    case Status::kWarn:
      return "WARN";
  }
  return "ERROR";
}

int severity(Status s) {
  switch (s) {
    case Status::kError:
      return 5;
    case Status::kFail:
      return 4;
    case Status::kNew:
      return 3;
    case Status::kFlaky:
      return 2;
    case Status::kWarn:
      return 1;
    case Status::kPass:
      return 0;
  }
  return 5;
}

Status worst(Status a, Status b) { return severity(a) >= severity(b) ? a : b; }

bool awaits_approval(Status s) {
  return s == Status::kFail || s == Status::kNew || s == Status::kWarn;
}

Status parse_status(std::string_view name) {
  for (Status s : {Status::kPass, Status::kFail, Status::kNew, Status::kError, Status::kFlaky,
                   Status::kWarn}) {
    if (status_name(s) == name) return s;
  }
  throw std::invalid_argument("unknown status '" + std::string(name) + "'");
}

std::string golden_hash(std::span<const unsigned char> bytes) {
  return ContentHash().add(bytes).hex();
}

namespace {

// One golden against the render; kError when either cannot be read.
ImageVerdict against(std::string_view image, std::span<const unsigned char> render_bytes,
                     const ReadGolden& golden, const Tolerance& t, bool want_diff,
                     const Counted* counted) {
  const fs::path& golden_file = golden.file;
  const std::vector<unsigned char>& bytes = golden.bytes;
  ImageVerdict v;
  v.image = std::string(image), v.golden = golden_file;
  try {
    if (!golden.error.empty()) throw std::runtime_error(golden.error);
    v.golden_hash = golden_hash(bytes);
    comparison::Options o;
    o.want_diff = o.want_heatmap = o.want_difference_views = want_diff;
    o.counted = counted;
    if (!t.regions.empty()) o.region_map = region_map(golden_file, image);
    static_cast<comparison::Comparison&>(v) =
        comparison::run(comparison::Input::file("the render", render_bytes),
                        comparison::Input::file(golden_file.string(), bytes), t, o);
    v.status = v.verdict == comparison::Verdict::kSame   ? Status::kPass
               : v.verdict == comparison::Verdict::kWarn ? Status::kWarn
                                                         : Status::kFail;
    v.message = v.comparison::Comparison::message();
  } catch (const std::exception& e) {
    v.status = Status::kError;
    v.message = e.what();
  }
  return v;
}

// How far from passing: gates failed first, then Resemble's mismatch.
bool closer(const ImageVerdict& a, const ImageVerdict& b) {
  const auto failed = [](const ImageVerdict& v) {
    return std::ranges::count_if(v.outcomes, [](const metric::Outcome& o) { return !o.pass; });
  };
  if (failed(a) != failed(b)) return failed(a) < failed(b);
  return a.mismatch_percent < b.mismatch_percent;
}

}  // namespace

ImageVerdict judge(std::string_view image, std::span<const unsigned char> render_bytes,
                   const std::vector<ReadGolden>& goldens, const Tolerance& tolerance,
                   bool want_diff, const Counted* counted) {
  if (goldens.empty()) {
    ImageVerdict v;
    v.image = std::string(image), v.status = Status::kNew, v.message = "no golden yet";
    return v;
  }
  // Every accepted golden is read, even after one passes: a damaged golden or variant is an
  // error to repair, not something another variant may hide.
  std::vector<ImageVerdict> tried;
  for (const ReadGolden& g : goldens)
    tried.push_back(against(image, render_bytes, g, tolerance, want_diff, counted));
  for (const ImageVerdict& v : tried) {
    if (v.status == Status::kError) return v;
  }
  for (ImageVerdict& v : tried) {
    if (v.status == Status::kPass) {
      v.heatmap = {};  // maps are for failures and warnings
      v.views.reset();
      return v;
    }
  }
  // A variant that passes with a warning before any that fails.
  if (const auto warning = std::ranges::find(tried, Status::kWarn, &ImageVerdict::status);
      warning != tried.end()) {
    return *warning;
  }
  // None passed: report the closest golden.
  return *std::min_element(tried.begin(), tried.end(), closer);
}

}  // namespace aosuite::harness
