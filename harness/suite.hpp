// A suite: the cases (scene x view x technique x parameters x resolution) the harness renders
// and checks against goldens, each with its tolerance. Read from suites/*.toml.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compare/metric.hpp"
#include "compare/resemble.hpp"
#include "renderer/scene/scene.hpp"
#include "renderer/technique.hpp"

namespace aosuite::harness {

// A tolerance class of a region map: the golden's <image>.regions.png beside it paints each
// pixel with a class's colour (black: no class); the class's metric gates hold over its pixels,
// and the tolerance's own metric gates over the unpainted ones.
struct Region {
  std::string name;
  std::array<int, 3> color{};  // R, G, B, not all 0
  std::vector<metric::Gates> gates;
};

// How far a render may stray from its golden and still pass: Resemble's gate, the metrics'
// gates, or both (all must hold).
struct Tolerance {
  // Resemble's gate (mode, max_mismatch_percent, max_channel_delta) holds; off when a suite
  // gives only metric gates. PNG images only.
  bool resemble = true;
  std::vector<metric::Gates> gates;  // e.g. flip = { max_mean = 0.02 }, rmse = { max = 0.01 }
  // Percentages and means over geometry pixels only (the G-buffer's depth says which), so sky
  // does not dilute them. Scene cases only.
  bool foreground_only = false;
  std::vector<Region> regions;                  // empty: no region map is read
  resemble::Mode mode = resemble::Mode::kLess;  // any Resemble.js mode
  double max_mismatch_percent = 0;              // Resemble's rawMisMatchPercentage, inclusive
  int max_channel_delta = 255;                  // largest |new - golden| of any RGBA channel
  std::vector<resemble::Box> ignore;            // left, top, right, bottom, in pixels
  std::filesystem::path
      mask;  // pixels where this PNG is not black (any of R, G, B > 0) are ignored
};

// The images of a case that can be gated against goldens. ao_float is the AO term as float EXR
// (ao_float.exr), rendered only for cases that gate it, by metric gates only.
inline constexpr std::array<const char*, 4> kImageNames{"no_ao", "with_ao", "ao_only", "ao_float"};
// The region map beside a golden: <image>.regions.png in its folder.
std::filesystem::path region_map(const std::filesystem::path& golden, std::string_view image);
// The file type of a render's image: ".exr" for ao_float, else ".png".
std::string render_ext(std::string_view image);

// Where an image case's images come from instead of a scene: files a command writes, or files
// already on disk. Each image is named by its file's stem (chart.png -> chart).
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

struct Case {
  std::string id;  // scene-view-technique-WxH[-name], or an image case's name; names its folder
  std::shared_ptr<const ImageSource> source;         // set for image cases (no scene then)
  nlohmann::json values = nlohmann::json::object();  // an image case's params, typed
  std::shared_ptr<const renderer::Scene> scene;
  std::string scene_source;  // the built-in name or the scene file, as the suite says it
  std::string view;
  renderer::Technique technique{};
  renderer::AoParams params;
  std::map<std::string, std::string> param_overrides;  // as written in the suite, for reports
  int width = 0, height = 0;
  std::vector<std::string> images;  // which of kImageNames are gated (image cases: every image)
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
  std::string check_args;        // what follows "aosuite check " to list its cases
  std::vector<Skipped> skipped;  // folder mode: files under either folder that are no case
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

// Parses and expands a suite file. Throws std::runtime_error "file:line:col: reason" for
// malformed TOML, unknown keys, wrong types, unknown scenes/views/techniques/parameters,
// impossible sizes and duplicate case ids.
Suite load_suite(const std::filesystem::path& file);

}  // namespace aosuite::harness
