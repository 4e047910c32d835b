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
#include "compare/tolerance.hpp"

namespace aosuite::harness {

using comparison::Region;
using comparison::Tolerance;
using comparison::WarnLimits;

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
  std::vector<std::string> env;  // environment variables the command reads: their values too
  // Whether the case says what its command reads (`inputs` or `env`, even empty): a case that
  // does not is never reused, since anything it reads may have changed.
  bool declared = false;
  double timeout_seconds = 60;
  std::vector<std::filesystem::path> files;  // per image, without a command: a file on disk
  std::filesystem::path dir;                 // the suite's folder ({suite_dir}), absolute
  bool follow_links = false;                 // the suite's follow_links (Suite)
  // Folder mode: the one expected file that stands in for the goldens folder (may not exist),
  // and whether the actual file is missing (the image was deleted).
  std::filesystem::path golden_file;
  bool deleted = false;
  std::string path;  // folder mode: the relative path both folders share
  // Each image's file type (".png", ".exr", ...), by image name: a command may write one
  // render as frame.png and frame.exr, each judged by the tolerance for its kind.
  std::map<std::string, std::string> exts;
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
  // Which [[case]] of the suite file made it (0 first): the ids one [[case]] expands into share
  // its [case.tolerance], so `tolerances suggest` writes them one table. Folder mode: its index.
  int table = 0;
};

// A file folder mode left out, and why (a link, not a regular file, not a PNG or EXR).
struct Skipped {
  std::string path;  // "actual/sub/a.jpg"
  std::string why;
};

struct Suite {
  std::string name;
  std::filesystem::path file;
  // The suite's `goldens` key (relative to the suite file), else goldens/<name> beside the
  // suite file, from any current directory; `--goldens` replaces it (goldens_given).
  std::filesystem::path goldens;
  bool goldens_given = false;
  // `follow_links = true`: links out of the suite's folder, its goldens folder or a command's
  // {out} are followed; by default each is an error naming it (common/file_io.hpp).
  bool follow_links = false;
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
// most kMaxNameLength characters.
inline constexpr std::size_t kMaxNameLength = 200;
bool valid_name(std::string_view name);
// Why `name` is not a valid_name() ("is 230 characters long, ..."); empty when it is.
std::string name_problem(std::string_view name);

}  // namespace aosuite::harness
