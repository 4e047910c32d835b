// Kinds of suite case beyond files and commands, which a higher layer registers: the AO bench
// registers rendered scenes (ao/scene_cases.hpp). The harness reads what every case shares (name,
// size, params, tolerance), hands the rest of a [[case]] table to the kind whose key it holds,
// and later asks the kind for the case's images: it never knows what makes them.
#pragma once

#include <toml++/toml.h>

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/toml_reader.hpp"
#include "harness/results.hpp"

namespace aosuite::harness {

// A case's images as their files' bytes (PNG, EXR, ...) and, where already decoded, their
// 8-bit pixels, by image name.
struct CaseImages {
  std::map<std::string, std::vector<unsigned char>> bytes;
  std::map<std::string, RgbaImage> rgba;
};

// The part of one case that its kind owns (for the AO bench: scene, view, technique, params).
class MadeCase {
 public:
  virtual ~MadeCase() = default;
  // Everything the images depend on, given the run's environment (its GL implementation).
  virtual std::string input_hash(const Case& c, const std::string& environment) const = 0;
  // The images kept in the report folder: the gated ones, and "foreground" (foreground_only's
  // mask: white where the pixel counts) when the tolerance asks for it.
  virtual std::vector<std::string> kept_images(const Case& c) const = 0;
  virtual std::string ext(std::string_view image) const = 0;  // ".png", ".exr"
  // What the report and results.json say of the case: labels and typed params.
  virtual void describe(const Case& c, CaseResult& r) const = 0;
};

// Makes a kind's images on one thread (and holds what that needs there: a GL context).
class Maker {
 public:
  virtual ~Maker() = default;
  // Writes c's kept images into case_dir and `out`; fills r's times and figures.
  virtual void make(const Case& c, const std::filesystem::path& case_dir, CaseResult& r,
                    CaseImages& out) = 0;
};

// A [[case]] table as a kind sees it: the shared fields are read (`base`: width, height,
// tolerance, params as written), the kind reads its own keys from `table` over `defaults`.
struct CaseTable {
  const TomlReader& reader;
  std::filesystem::path dir;    // the suite's folder
  const toml::table* defaults;  // [defaults], or null
  const toml::table& table;
  Case base;
  std::map<std::string, toml::source_region> param_at;  // where each param was written
  std::string suffix;                                   // "-<name>" when the case is named
  // What a kind keeps while one suite is read (scenes shared by its cases), by its own keys.
  std::map<std::string, std::shared_ptr<const void>>& memo;
};

// What a run's results say of the machine that made the images, and the platform key its
// goldens are looked up under (empty: generic goldens only).
struct Environment {
  std::string description, platform;
};

class CaseKind {
 public:
  virtual ~CaseKind() = default;
  virtual std::string_view name() const = 0;  // results' `kind`: "render"
  virtual std::string_view key() const = 0;   // a [[case]] with this key is this kind's: "scene"
  // The keys it reads besides the shared ones: in a [[case]] and in [defaults].
  virtual std::vector<std::string_view> case_keys() const = 0;
  virtual std::vector<std::string_view> default_keys() const = 0;
  // Appends the cases one table expands to, each with its `made` part and its id; errors
  // through t.reader.fail (file:line:col).
  virtual void expand(const CaseTable& t, std::vector<Case>& out) const = 0;
  // A maker for one thread. The first of a run also fills `env` (null for later ones).
  virtual std::unique_ptr<Maker> maker(Environment* env) const = 0;
  // The report's section over this kind's cases (HTML, "" for none): the AO bench's tables.
  virtual std::string report_section(const RunResults& run,
                                     const std::filesystem::path& report_dir) const = 0;
};

// Whether a result's kind is the harness's own: "files", "command" or "folder".
bool is_image_kind(std::string_view name);

void register_kind(std::unique_ptr<CaseKind> kind);
// What registers the kinds a build has beyond files and commands (loading the AO bench's
// library); run once, the first time a suite or report names something no kind knows.
void set_kind_loader(std::function<void()> loader);
// Runs the loader if it has not run yet; returns whether it ran. A build without the AO bench
// has none, and then only files and commands make cases. Nothing is loaded for a suite or
// report that needs no other kind: an image-only run maps no GL.
bool load_kinds();
// The kind whose key a [[case]] table holds, or whose name a result has, loading the kinds
// when no registered one matches; null if none.
const CaseKind* kind_for(const toml::table& case_table);
const CaseKind* find_kind(std::string_view name);
// The registered kinds, and every key they read in [defaults] / [[case]] (loading nothing).
std::vector<std::string_view> kinds_default_keys();
std::vector<std::string_view> kinds_case_keys();
std::vector<const CaseKind*> kinds();

}  // namespace aosuite::harness
