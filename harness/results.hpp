// What a run of a suite found, case by case; saved as results.json in the report folder so a
// report can be rebuilt or merged from shards, and so an unchanged case can be skipped.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "harness/judge.hpp"
#include "harness/pass_record.hpp"

namespace aosuite::harness {

// How long one stage of making a case's images took (a render pass's GPU time).
struct Timing {
  std::string stage;
  double ms = 0;
};

// A failing attempt of a case that was run again (--retries): what it said and the images it
// made, kept under attempt<k>_ names in the case's report folder.
struct Attempt {
  Status status = Status::kError;
  std::string message;
  std::map<std::string, std::string> files;  // as CaseResult::files
};

struct CaseResult {
  std::string id;
  // "command" (files a command wrote), "files" (files on disk), "folder" (folder mode: one
  // image paired by relative path), or a registered kind's name ("render": a scene).
  std::string kind;
  // What its kind says the case is, in order (scene, view, technique): the report shows them.
  std::vector<std::pair<std::string, std::string>> labels;
  // What an image case shows: its command line (shell-quoted), its files, or folder mode's
  // relative path.
  std::string source;
  int width = 0, height = 0;
  // Every parameter the render used (an image case's params), with its type: numbers are
  // numbers, lists arrays.
  std::map<std::string, nlohmann::json> params;
  Tolerance tolerance;
  Status status = Status::kError;  // the worst of the images'
  std::string message;             // render error, or the first failing image's reason
  std::vector<ImageVerdict> images;
  // Files in the report folder, by role: no_ao, with_ao, ao_only, golden:<image>, diff:<image>.
  std::map<std::string, std::string> files;
  std::vector<Timing> times;
  // Numbers its kind measured beside the verdict, for its report section (the AO bench: how
  // much of the picture AO changes, the thesis's Tables 11-14).
  std::map<std::string, double> figures;
  std::string input_hash, judge_hash;  // what the render and the verdict depended on
  // The content hash of each image kept in the case's report folder, as this run made or found
  // it: a later run reuses those files only while they still hold exactly these bytes (a bless,
  // or a run killed before its cache was saved, may have replaced them since).
  std::map<std::string, std::string> image_hashes;
  // A rendered case's passes in pipeline order and the content hash of what each wrote
  // (gbuffer, ao, blur, blend): bless keeps them beside the goldens, and a failing case names
  // the first pass that differs from its golden's.
  PassHashes pass_hashes;
  bool reused = false;  // inputs and goldens unchanged: nothing re-rendered
  // Why an unchanged-looking case was made again instead of reused ("" when it was not):
  // a command case that declares neither `inputs` nor `env` is never reused.
  std::string not_reused;
  double seconds = 0;
  std::string bless_command;             // set for cases that are not passing
  int exit_status = -1;                  // a command case's exit status (-1: none ran)
  std::string command_stderr;            // the end of what its command wrote to stderr
  int attempts = 1;                      // how often it ran (--retries)
  std::vector<Attempt> failed_attempts;  // each attempt before the last, in order
  bool kept = false;     // bless: the case passes, so its goldens were left as they were
  bool deleted = false;  // folder mode: the image is only in the expected folder (a FAIL)
  // --report-images failures and the case passed: its numbers are kept, its images are not
  // (each verdict still names its golden).
  bool images_left_out = false;
};

struct RunResults {
  std::string suite, platform;
  // Absolute, so `bless --failed --report DIR` finds them from any directory: the suite file
  // and its goldens folder, or folder mode's --actual and --expected (expected_folder empty
  // for a suite file).
  std::string suite_file, goldens, expected_folder;
  std::string environment;  // what made the images (the GL implementation), if a kind says
  // "aosuite bless SUITE [--goldens DIR]", shell-quoted: what the printed bless commands start
  // with.
  std::string bless_prefix;
  std::string shard;  // "i/n", empty when not sharded
  // The command that accepts cases from this report's images: "aosuite bless SUITE
  // --from-report --report DIR"; the page adds --filter.
  std::string approve_prefix;
  std::vector<CaseResult> cases;
};

// Images are kept as paths relative to the report folder; results.json never holds pixels.
// Free text (messages, paths, the GL string) is written through printable(), so the JSON is
// valid UTF-8 whatever bytes a path holds. Reading checks what becomes a path: a case id must be
// a valid_name() and each file must be <case id>/<valid name>, else std::runtime_error.
nlohmann::json to_json(const CaseResult& c);
CaseResult case_from_json(const nlohmann::json& j);
nlohmann::json to_json(const RunResults& r);
RunResults run_from_json(const nlohmann::json& j);

// Writes a report file under a temporary name and renames it into place: never seen half
// written, but not synced (a report is rebuilt by the next run; goldens are synced).
void write_report_file(const std::filesystem::path& path, std::span<const unsigned char> bytes);
// write_report_file unless the file there already holds `bytes`: an unchanged image costs no
// write (a rename over a file can wait for the disk).
void keep_in_report(const std::filesystem::path& file, const std::vector<unsigned char>& bytes);

// Reads `dir`/results.json; throws naming the file if it is missing or malformed.
RunResults read_results(const std::filesystem::path& dir);

// What results.json records of the suite's paths: absolute, as bless may run elsewhere.
std::string absolute_path(const std::filesystem::path& p);
void write_results(const std::filesystem::path& dir, const RunResults& r);

struct Counts {
  int pass = 0, fail = 0, fresh = 0, error = 0, flaky = 0, warn = 0;
  int deleted = 0;  // of `fail`: folder mode's images only in the expected folder
};
Counts count(const RunResults& r);
// 0 all passed (flaky and warning ones too), 1 any failed or new, 2 any could not be judged.
int exit_code(const Counts& c);

}  // namespace aosuite::harness
