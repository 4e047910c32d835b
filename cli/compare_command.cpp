// `aosuite compare A B`: Resemble.js 5.0.0's comparison of two PNGs, and `--batch` for many.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/compare_metrics.hpp"
#include "common/file_io.hpp"
#include "common/thread_beside.hpp"
#include "compare/band_compare.hpp"
#include "compare/resemble.hpp"
#include "compare/resemble_json.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"
#include "image/png_layout.hpp"

namespace aosuite::cli {
namespace {

namespace rs = aosuite::resemble;

// Options are kept as text and parsed here, so that every bad value gets one accurate line.
struct CompareArgs {
  std::string a, b, batch, diff, mode = "default", tolerance, error_type = "flat", error_color,
                                 ignore_color, canvas_alpha = "none";
  std::vector<std::string> bounding_boxes, ignored_boxes, metrics, gates, limits;
  std::string heatmap, flip_pooling = "exact";
  std::string large_image_threshold = "1200", return_early = "0", transparency = "1",
              threshold = "0", memory_limit = "1024";
  bool json = false;
};

// A finite decimal number, all of `text`: not "nan" or "inf", nor one a double cannot hold.
double finite_number(const std::string& text, const std::string& what) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = text.empty() || std::isspace(static_cast<unsigned char>(text[0]))
                       ? 0
                       : std::strtod(begin, &end);
  if (end == nullptr || end == begin || *end != '\0') {
    throw std::invalid_argument(fmt::format("{} '{}' is not a number", what, text));
  }
  if (errno == ERANGE) {
    throw std::invalid_argument(fmt::format("{} '{}' is out of range ({} for a double)", what, text,
                                            std::isinf(v) ? "too large" : "too close to zero"));
  }
  if (!std::isfinite(v)) {
    throw std::invalid_argument(fmt::format("{} '{}' is not a finite number", what, text));
  }
  return v;
}

double number_in(const std::string& text, const char* what, double min, double max) {
  const double v = finite_number(text, what);
  if (v < min || v > max) {
    throw std::invalid_argument(
        fmt::format("{} '{}' is out of range ({} to {})", what, text, min, max));
  }
  return v;
}

std::vector<double> numbers(const std::string& text, std::size_t min, std::size_t max,
                            const char* what) {
  std::vector<double> out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t comma = std::min(text.find(',', pos), text.size());
    out.push_back(
        finite_number(text.substr(pos, comma - pos), fmt::format("{} '{}':", what, text)));
    pos = comma + 1;
  }
  if (out.size() < min || out.size() > max) {
    throw std::invalid_argument(
        fmt::format("{} '{}' needs {} to {} numbers", what, text, min, max));
  }
  return out;
}

std::vector<rs::Box> parse_boxes(const std::vector<std::string>& specs, const char* what) {
  std::vector<rs::Box> out;
  for (const auto& s : specs) {
    const auto v = numbers(s, 4, 4, what);
    out.push_back({v[0], v[1], v[2], v[3]});
  }
  return out;
}

// Resemble's errorType names; Resemble itself treats any other name as flat, but on the
// command line an unknown one is a typing mistake.
rs::ErrorType error_type_option(const std::string& name) {
  for (const char* known :
       {"flat", "movement", "flatDifferenceIntensity", "movementDifferenceIntensity", "diffOnly"}) {
    if (name == known) return rs::parse_error_type(name);
  }
  throw std::invalid_argument(
      fmt::format("--error-type '{}' is unknown (expected flat, movement, flatDifferenceIntensity, "
                  "movementDifferenceIntensity or diffOnly)",
                  name));
}

rs::Options options_from(const CompareArgs& args) {
  rs::Options o;
  // `--limit mode=M` is the tolerance's mode, so it is Resemble's too: the same as --mode M.
  std::string mode = args.mode;
  for (const std::string& spec : args.limits) {
    if (!spec.starts_with("mode=")) continue;
    if (mode != "default" && mode != spec.substr(5))
      throw std::invalid_argument("--mode " + mode + " and --limit " + spec + " disagree");
    mode = spec.substr(5);
  }
  if (mode != "default") o.modes = {rs::parse_mode(mode)};
  // Resemble applies a custom tolerance only together with an ignore mode and silently
  // ignores it otherwise (resemblejs-semantics.md). Honouring it without a mode would
  // break parity with Resemble; ignoring it would hide the mistake. So it is an error.
  if (!args.tolerance.empty() && o.modes.empty()) {
    throw std::invalid_argument(
        "--tolerance needs --mode (Resemble applies a custom tolerance only with a mode)");
  }
  if (!args.tolerance.empty()) {
    nlohmann::json t;
    try {
      t = nlohmann::json::parse(args.tolerance);
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(fmt::format("--tolerance is not JSON: {}", e.what()));
    }
    rs::apply_json_options({{"tolerance", t}}, o);
  }
  o.large_image_threshold =
      number_in(args.large_image_threshold, "--large-image-threshold", 0, 1e9);
  o.error_type = error_type_option(args.error_type);
  if (!args.error_color.empty()) {
    const auto c = numbers(args.error_color, 3, 4, "--error-color");
    o.error_color = {c[0], c[1], c[2], c.size() == 4 ? c[3] : 255};
  }
  o.transparency = finite_number(args.transparency, "--transparency");
  if (!args.bounding_boxes.empty())
    o.bounding_boxes = parse_boxes(args.bounding_boxes, "--bounding-box");
  if (!args.ignored_boxes.empty())
    o.ignored_boxes = parse_boxes(args.ignored_boxes, "--ignored-box");
  if (!args.ignore_color.empty()) {
    const auto c = numbers(args.ignore_color, 3, 4, "--ignore-areas-colored-with");
    o.ignore_areas_colored_with = rs::Color{c[0], c[1], c[2], 255};
  }
  o.return_early_threshold = number_in(args.return_early, "--return-early-threshold", 0, 100);
  o.canvas_alpha = parse_canvas_alpha(args.canvas_alpha);
  return o;
}

// What the run may hold: both files, and when they are decoded whole, both images and what
// the comparison allocates (the diff image and its PNG encoding among it).
struct Budget {
  std::uint64_t bytes;
};

constexpr std::uint64_t kMiB = 1 << 20;

// Refuses, before anything is decoded, a comparison of whole images that would go over the
// budget, naming the file that takes it over.
void check_budget(const std::string& a, std::span<const unsigned char> bytes_a,
                  const std::string& b, std::span<const unsigned char> bytes_b, bool identical,
                  const rs::Options& o, Budget budget) {
  const PngHeader ha = peek_png_header(bytes_a, a), hb = peek_png_header(bytes_b, b);
  const ImageSize sa{int(std::min<std::uint32_t>(ha.width, 1u << 30)),
                     int(std::min<std::uint32_t>(ha.height, 1u << 30))};
  const ImageSize sb{int(std::min<std::uint32_t>(hb.width, 1u << 30)),
                     int(std::min<std::uint32_t>(hb.height, 1u << 30))};
  const std::uint64_t pixels_a = std::uint64_t(sa.width) * std::uint64_t(sa.height);
  const std::uint64_t pixels_b = std::uint64_t(sb.width) * std::uint64_t(sb.height);
  const std::uint64_t need_a = bytes_a.size() + 4 * pixels_a;
  if (need_a > budget.bytes) {
    throw FileError(
        fmt::format("{}: {}x{} pixels need {} MiB decoded, over the {} MiB memory "
                    "budget (--memory-limit MIB)",
                    a, ha.width, ha.height, (need_a + kMiB - 1) / kMiB, budget.bytes / kMiB));
  }
  std::uint64_t need = need_a + rs::working_bytes(sa, sb, o);
  if (!identical) need += bytes_b.size() + 4 * pixels_b;
  if (o.produce_diff) {  // the encoded diff PNG, at most about the diff image's size
    need += 4 * std::max<std::uint64_t>(sa.width, sb.width) * std::max(sa.height, sb.height);
  }
  if (need > budget.bytes) {
    throw FileError(
        fmt::format("{}: {}x{} pixels: comparing it with {}{} needs {} MiB, over "
                    "the {} MiB memory budget (--memory-limit MIB)",
                    b, hb.width, hb.height, a, o.produce_diff ? " and a diff image" : "",
                    (need + kMiB - 1) / kMiB, budget.bytes / kMiB));
  }
}

// The one comparison of the two files (b, the second, against a, the reference) with
// Resemble's options for its result; stages the diff image when asked (the caller commits its
// outputs together). The memory budget is checked before any PNG is decoded.
comparison::Comparison compare_pair(const std::string& a, const std::string& b, rs::Options o,
                                    const comparison::Tolerance& t, const std::string& diff_path,
                                    bool want_heatmap, bool tool_pooling, Budget budget,
                                    StagedFiles& outputs) {
  const MappedFile file_a(a, budget.bytes), file_b(b, budget.bytes);
  const auto bytes_a = file_a.bytes(), bytes_b = file_b.bytes();
  o.produce_diff = !diff_path.empty();
  if (o.produce_diff && o.return_early_threshold > 0) {
    throw std::invalid_argument("no diff image: --return-early-threshold disables it");
  }
  const bool identical = std::ranges::equal(bytes_a, bytes_b);
  if (is_png(bytes_a) && is_png(bytes_b) && !(identical && !o.produce_diff)) {
    check_budget(a, bytes_a, b, bytes_b, identical, o, budget);  // identical: a band at a time
  }
  comparison::Options options;
  options.want_diff = o.produce_diff, options.want_heatmap = want_heatmap;
  options.resemble_options = &o, options.max_bytes = budget.bytes;
  options.tool_pooling = tool_pooling;
  comparison::Comparison c = comparison::run(comparison::Input::file(b, bytes_b),
                                             comparison::Input::file(a, bytes_a), t, options);
  if (o.produce_diff) {
    const auto is_float = [](const std::string& kind) { return kind.starts_with("float"); };
    if (c.diff.empty() && (is_float(c.expected_kind) || is_float(c.actual_kind))) {
      throw std::invalid_argument((is_float(c.expected_kind) ? a : b) +
                                  ": no diff image for float images");
    }
    if (c.diff.empty()) {  // another kind of image: the verdict says why, as for the heat map
      fmt::print(stderr, "aosuite compare: {}: no diff image written ({})\n", diff_path,
                 c.message());
    } else {
      outputs.stage(diff_path, encode_png_rgba8(c.diff, 3));
    }
  }
  return c;
}

Budget budget_from(const CompareArgs& args) {
  const double mib = number_in(args.memory_limit, "--memory-limit", 1, 1 << 20);
  return {static_cast<std::uint64_t>(mib) * kMiB};
}

void print_human(const std::string& a, const std::string& b, const comparison::Comparison& c) {
  if (const std::optional<rs::Result>& r = c.resemble) {
    fmt::print("{} vs {}: {}% mismatch ({} pixels)", a, b, r->mismatch_percentage,
               r->mismatch_count);
    if (!r->same_dimensions) {
      fmt::print(", sizes differ by {}x{}", r->width_difference, r->height_difference);
    }
    if (r->mismatch_count) {
      const rs::Bounds& d = r->diff_bounds;
      fmt::print(", bounds x {}..{} y {}..{}", d.left, d.right, d.top, d.bottom);
    }
    if (c.comparable && !c.identical) {
      fmt::print(", max channel delta {}, mean shift {:.3g}", c.max_channel_delta, c.mean_shift);
    }
    fmt::print(" -> {}\n", c.same() ? "same" : "different");
  }
  for (const std::string& line : metric_lines(c)) fmt::print("{} vs {}: {}\n", a, b, line);
  if (!c.same()) fmt::print("failed: {}\n", c.message());
  if (!c.changes.empty()) fmt::print("changed: {}\n", comparison::changes_text(c.changes, 5));
}

// The JSON: Resemble.js's own object, key for key, then the metrics measured, then what the
// exit status says: "verdict" ("same" or "different") and the limits that failed.
std::string json_line(const comparison::Comparison& c, nlohmann::ordered_json extra) {
  for (const metric::Measurement& m : c.measured) extra[m.metric] = m.json();
  extra["verdict"] = c.same() ? "same" : "different";
  extra["failed_gates"] = c.failed;
  if (!c.changes.empty()) extra["changes"] = comparison::changes_json(c.changes);
  return c.resemble ? rs::result_json(*c.resemble, extra) : extra.dump();
}

comparison::Tolerance tolerance_of(const CompareArgs& args, const std::string& heatmap) {
  return tolerance_from({.metrics = args.metrics,
                         .gates = args.gates,
                         .limits = args.limits,
                         .heatmap = heatmap,
                         .threshold = number_in(args.threshold, "--threshold", 0, 100),
                         .mode = args.mode});
}

int run_single(const CompareArgs& args) {
  const comparison::Tolerance t = tolerance_of(args, args.heatmap);
  StagedFiles outputs;  // the diff and the heat map, both or neither
  const comparison::Comparison c =
      compare_pair(args.a, args.b, options_from(args), t, args.diff, !args.heatmap.empty(),
                   args.flip_pooling == "tool", budget_from(args), outputs);
  if (!args.heatmap.empty()) {
    if (c.heatmap.empty()) {  // nothing comparable was measured: the verdict says why
      fmt::print(stderr, "aosuite compare: {}: no heat map written ({})\n", args.heatmap,
                 c.message());
    } else {
      outputs.stage(args.heatmap, encode_png_rgba8(c.heatmap, 3));
    }
  }
  outputs.commit();
  if (args.json) {
    fmt::print("{}\n", json_line(c, nlohmann::ordered_json::object()));
  } else {
    print_human(args.a, args.b, c);
  }
  return c.same() ? kExitSame : kExitDifferent;
}

// resemble-oracle's batch format: `A<TAB>B`, `A B`, or a JSON object with a, b, id, diff
// (or diffRaw) and option keys. Blank lines and # comments are skipped.
int run_batch(const CompareArgs& args) {
  const comparison::Tolerance t = tolerance_of(args, "");
  const rs::Options defaults = options_from(args);
  const Budget budget = budget_from(args);
  if (!args.heatmap.empty())
    throw std::invalid_argument("--heatmap writes one file: not with --batch");
  std::ifstream file;
  if (args.batch != "-") {
    file.open(args.batch);
    if (!file) throw FileError(fmt::format("{}: cannot open batch file", args.batch));
  }
  std::istream& in = args.batch == "-" ? std::cin : file;
  int worst = kExitSame;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    nlohmann::ordered_json extra = nlohmann::ordered_json::object();
    try {
      rs::Options o = defaults;
      std::string a, b, diff;
      if (line[first] == '{') {
        const auto j = nlohmann::json::parse(line);
        a = j.value("a", ""), b = j.value("b", "");
        diff = j.value("diffRaw", j.value("diff", ""));
        if (j.contains("id")) extra["id"] = j["id"];
        rs::apply_json_options(j, o);
      } else {
        const std::size_t sep =
            line.find('\t') != std::string::npos ? line.find('\t') : line.find(' ', first);
        if (sep == std::string::npos) throw std::invalid_argument("expected two paths");
        a = line.substr(first, sep - first);
        b = line.substr(line.find_first_not_of(" \t", sep));
        b.erase(b.find_last_not_of(" \t\r") + 1);
      }
      if (a.empty() || b.empty()) throw std::invalid_argument("needs both 'a' and 'b'");
      extra["a"] = a, extra["b"] = b;
      StagedFiles outputs;
      const comparison::Comparison c =
          compare_pair(a, b, o, t, diff, false, args.flip_pooling == "tool", budget, outputs);
      outputs.commit();
      fmt::print("{}\n", json_line(c, extra));
      if (!c.same()) worst = std::max(worst, kExitDifferent);
    } catch (const std::exception& e) {
      extra["error"] = fmt::format("{}: line {}: {}", args.batch, line_no, e.what());
      fmt::print("{}\n", extra.dump());
      worst = kExitError;
    }
  }
  return worst;
}

}  // namespace

void add_compare_command(CLI::App& app, int& rc) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Compare two images exactly as Resemble.js 5.0.0 does, and measure FLIP, SSIM, RMSE or\n"
      "PSNR (--metric) at the images' full precision (8- or 16-bit, float).\n"
      "Exit status: 0 same under the one tolerance (docs/compare.md: mismatch <= --threshold,\n"
      "channel delta <= 8, mean shift <= 0.5, mean delta <= 0.25 levels, same size and kind,\n"
      "every --gate), 1 different, 2 error. --metric alone measures without gating.");
  cmd->add_option("a", args->a, "first image (PNG, EXR, JPEG, TIFF, WebP, HDR, TGA, BMP)")
      ->option_text("FILE");
  cmd->add_option("b", args->b, "second image")->option_text("FILE");
  cmd->add_option("--batch", args->batch,
                  "compare the pairs listed in FILE (- for stdin), one JSON line out per pair; "
                  "the format of resemble-oracle --batch")
      ->option_text("FILE");
  cmd->add_option("--mode", args->mode,
                  "Resemble's ignore mode: nothing|less|colors|antialiasing|alpha; without one, "
                  "Resemble's own defaults (the tolerances of less)")
      ->option_text("MODE");
  cmd->add_option("--tolerance", args->tolerance,
                  R"(JSON, e.g. '{"red":4,"minBrightness":4}'; like Resemble, only with a --mode)")
      ->option_text("JSON");
  cmd->add_option("--error-type", args->error_type,
                  "flat|movement|flatDifferenceIntensity|movementDifferenceIntensity|diffOnly "
                  "(default flat)")
      ->option_text("TYPE");
  cmd->add_option("--error-color", args->error_color, "the diff's colour (default 255,0,255,255)")
      ->option_text("R,G,B[,A]");
  cmd->add_option("--transparency", args->transparency,
                  "alpha factor of non-error pixels in the diff (default 1)")
      ->option_text("FACTOR");
  cmd->add_option("--bounding-box", args->bounding_boxes, "compare only inside (repeatable)")
      ->option_text("L,T,R,B");
  cmd->add_option("--ignored-box", args->ignored_boxes, "do not compare inside (repeatable)")
      ->option_text("L,T,R,B");
  cmd->add_option("--ignore-areas-colored-with", args->ignore_color,
                  "do not compare where the second image has this colour")
      ->option_text("R,G,B");
  cmd->add_option("--large-image-threshold", args->large_image_threshold,
                  "sample every 6th row/column above this many pixels a side in antialiasing "
                  "mode (default 1200); 0 = never")
      ->option_text("PIXELS");
  cmd->add_option("--return-early-threshold", args->return_early,
                  "stop once the mismatch % exceeds this (no diff image)")
      ->option_text("0..100");
  cmd->add_option("--canvas-alpha", args->canvas_alpha,
                  "what a canvas does to translucent pixels: none|chromium|node-canvas (default "
                  "none)")
      ->option_text("CANVAS");
  cmd->add_option("--metric", args->metrics,
                  fmt::format("measure these beside Resemble's comparison: {} (comma-separated "
                              "or repeated)",
                              metric::names()))
      ->option_text("NAME[,NAME...]");
  cmd->add_option("--gate", args->gates,
                  "METRIC.KEY=VALUE, all must hold beside Resemble's gate: max/min (the "
                  "metric's main value), max_STAT/min_STAT, allow_nonfinite=true; e.g. "
                  "flip.max_mean=0.02 (repeatable)")
      ->option_text("METRIC.KEY=VALUE");
  cmd->add_option("--limit", args->limits,
                  "KEY=VALUE, any limit of the one tolerance as a suite's [tolerance] names it: "
                  "max_channel_delta=255, max_mean_shift=1, shift_radius=1, "
                  "allow_kind_change=true (repeatable)")
      ->option_text("KEY=VALUE");
  cmd->add_option("--heatmap", args->heatmap, "write FLIP's error map (magma) as PNG")
      ->option_text("FILE");
  cmd->add_option("--flip-pooling", args->flip_pooling,
                  "exact (double sums) or tool: FLIP's mean and weighted percentiles summed in "
                  "float as NVlabs' FLIP tool does, printed to its 6 decimals")
      ->check(CLI::IsMember({"exact", "tool"}))
      ->option_text("exact|tool (default exact)");
  cmd->add_option("--diff", args->diff, "write the diff image (Resemble's raw buffer) as PNG")
      ->option_text("FILE");
  cmd->add_option("--threshold", args->threshold,
                  "largest Resemble mismatch % still judged the same (max_mismatch_percent)")
      ->option_text("0..100 (default 0)");
  cmd->add_option("--memory-limit", args->memory_limit,
                  "MiB the comparison may hold: files, decoded images, diff image (default 1024)")
      ->option_text("MIB");
  cmd->add_flag("--json", args->json, "print Resemble's result object as one JSON line");
  cmd->callback([args, &rc] {
    if (args->batch.empty() && (args->a.empty() || args->b.empty())) {
      throw CLI::ValidationError("needs two images, or --batch FILE");
    }
    try {
      rc = args->batch.empty() ? run_single(*args) : run_batch(*args);
    } catch (const std::exception& e) {
      fmt::print(stderr, "aosuite compare: {}\n", e.what());
      rc = kExitError;
    }
  });
}

}  // namespace aosuite::cli
