// A suite: the cases the harness makes (files, a command's outputs, or a registered kind's, such
// as the AO bench's rendered scenes) and checks against goldens, each with its tolerance. Read
// from suites/*.toml.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compare/metric.hpp"
#include "compare/resemble.hpp"

namespace aosuite::harness {

// A tolerance class of a region map: the golden's <image>.regions.png beside it paints each
// pixel with a class's colour (black: no class); the class's metric gates hold over its pixels,
// and the tolerance's own metric gates over the unpainted ones.
struct Region {
  std::string name;
  std::array<int, 3> color{};  // R, G, B, not all 0
  std::vector<metric::Gates> gates;
};

inline constexpr int kDefaultChannelDelta = 8;

// The warning tier, `[tolerance.warn]` (idiff's -warn beside -fail): tighter limits that a
// passing image may exceed and still pass, with a WARN status that exits 0, so a drift is seen
// before it fails. Only the limits it names are checked; its metric gates judge the whole image
// (with regions, the unpainted pixels), under the tolerance's Resemble mode.
struct WarnLimits {
  double max_mismatch_percent = 100;  // 100, 255, -1: not checked
  int max_channel_delta = 255;
  long long max_differing_pixels = -1;
  std::vector<metric::Gates> gates;
  bool resemble() const {
    return max_mismatch_percent < 100 || max_channel_delta < 255 || max_differing_pixels >= 0;
  }
  bool empty() const { return !resemble() && gates.empty(); }
};

// How far a render may stray from its golden and still pass: Resemble's gate, the metrics'
// gates, or both (all must hold).
struct Tolerance {
  // Resemble's gate (mode, max_mismatch_percent, max_channel_delta) holds; off when a suite
  // gives only metric gates. PNG images only.
  bool resemble = true;
  std::vector<metric::Gates> gates;  // e.g. flip = { max_mean = 0.02 }, rmse = { max = 0.01 }
  // Percentages and means over the pixels the case's "foreground" image marks (a rendered
  // scene's geometry), so sky does not dilute them. Only for kinds that keep such an image.
  bool foreground_only = false;
  std::vector<Region> regions;                  // empty: no region map is read
  resemble::Mode mode = resemble::Mode::kLess;  // any Resemble.js mode
  double max_mismatch_percent = 0;              // Resemble's rawMisMatchPercentage, inclusive
  // Largest |new - golden| of any RGBA channel. Resemble's default `less` mode ignores up to 16
  // levels per channel, so without a budget a global shading change of 12 levels passes: 8
  // unless the tolerance names a mismatch percentage alone (then any, as Resemble's gate).
  int max_channel_delta = kDefaultChannelDelta;
  // Two-sided budgets (verdict::ResembleAllowance): `channel_delta = [min, max]`,
  // `differing_pixels = [min, max]` or `max_differing_pixels = N`.
  int min_channel_delta = 0;
  long long min_differing_pixels = 0, max_differing_pixels = -1;  // -1: any
  std::vector<resemble::Box> ignore;  // left, top, right, bottom, in pixels
  std::filesystem::path
      mask;  // pixels where this PNG is not black (any of R, G, B > 0) are ignored
  WarnLimits warn;
};

// The region map beside a golden: <image>.regions.png in its folder.
std::filesystem::path region_map(const std::filesystem::path& golden, std::string_view image);

// Where an image case's images come from: files a command writes, or files already on disk.
// Each image is named by its file's stem (chart.png -> chart).
struct ImageSource {
  // argv, run without a shell in the case's output folder; {out}, {id}, {name}, {suite_dir},
  // {width}, {height} and {<param>} are replaced (shell-quoted inside `sh -c SCRIPT`).
  std::vector<std::string> command;
  std::vector<std::string> outputs;           // per image: the file the command writes in {out}
  std::vector<std::filesystem::path> inputs;  // files the command reads: their bytes are hashed
  double timeout_seconds = 60;
  std::vector<std::filesystem::path> files;  // per image, without a command: a file on disk
  std::filesystem::path dir;                 // the suite's folder ({suite_dir}), absolute
  // Folder mode: the one expected file that stands in for the goldens folder (may not exist),
  // and whether the actual file is missing (the image was deleted).
  std::filesystem::path golden_file;
  bool deleted = false;
  std::string path;  // folder mode: the relative path both folders share
  // The images' file type: ".png", or in folder mode ".exr", which is compared byte for byte
  // (no decoder here: identical or changed).
  std::string ext = ".png";
};

// Replaces the {placeholders} of an image case's command (`{{` and `}}` are braces). Throws
// std::invalid_argument naming an unknown placeholder. `quote`: shell-quote what is inserted.
std::string expand_placeholders(std::string_view text,
                                const std::map<std::string, std::string>& values, bool quote);

struct Case;
// An image case's placeholder values, {out} aside: {id}, {name}, {suite_dir}, {width},
// {height} and each of its params.
std::map<std::string, std::string> command_placeholders(const Case& k);

class CaseKind;
class MadeCase;

struct Case {
  std::string id;  // an image case's name, or what its kind makes of it; names its folder
  // Exactly one of: an image case's files or command, or a registered kind's part of the case.
  std::shared_ptr<const ImageSource> source;
  const CaseKind* kind = nullptr;
  std::shared_ptr<const MadeCase> made;
  nlohmann::json values = nlohmann::json::object();    // params as typed in the suite
  std::map<std::string, std::string> param_overrides;  // params as written in the suite
  int width = 0, height = 0;
  std::vector<std::string> images;  // the gated images (image cases: every image)
  Tolerance tolerance;
};

// A file folder mode left out, and why (a link, not a regular file, not a PNG or EXR).
struct Skipped {
  std::string path;  // "actual/sub/a.jpg"
  std::string why;
};

struct Suite {
  std::string name;
  std::filesystem::path file;
  // The suite's `goldens` key (relative to the suite file), else goldens/<name> relative to
  // the current directory, as reports/<name> is; `--goldens` replaces it (goldens_given).
  std::filesystem::path goldens;
  bool goldens_given = false;
  std::vector<Case> cases;
  // "aosuite bless SUITE" or "aosuite bless --actual A --expected E": how commands name it.
  std::string bless_prefix;
  std::string check_args;          // what follows "aosuite check " to list its cases
  std::vector<Skipped> skipped;    // folder mode: files under either folder that are no case
  std::filesystem::path expected;  // folder mode: --expected (`file` is --actual); else empty
};

// Folder mode (as reg-cli): one image case per PNG under `actual` or `expected`, paired by
// relative path; the expected file is its golden. Throws std::runtime_error naming a folder
// that cannot be read or two paths whose case ids collide.
Suite folder_suite(const std::filesystem::path& actual, const std::filesystem::path& expected,
                   const Tolerance& tolerance);

// Whether `name` is safe as one path component of a suite name, case id or variant tag:
// letters, digits, '-', '_', '.', not starting with '.' (so never "." or ".." nor hidden), at
// most 200 characters.
bool valid_name(std::string_view name);

}  // namespace aosuite::harness
