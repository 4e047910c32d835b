// bless: goldens written from fresh (or unchanged) images or from a report's, each case's all or
// nothing, and only where asked.
#include <fmt/format.h>

#include <stdexcept>

#include "common/file_io.hpp"
#include "harness/case_images.hpp"
#include "harness/case_verdict.hpp"
#include "harness/escape.hpp"
#include "harness/goldens.hpp"
#include "harness/reuse_cache.hpp"
#include "harness/run_cases.hpp"
#include "harness/runner.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

namespace {

void write_case_goldens(const Suite& suite, const Case& c, const std::string& platform,
                        const std::string& tag, const CaseImages& images, CaseResult& r) {
  const fs::path dir = c.source && !c.source->golden_file.empty()
                           ? c.source->golden_file.parent_path()
                           : suite.goldens / c.id;
  std::vector<GoldenWrite> writes;
  std::string written;
  std::vector<std::vector<unsigned char>> blank_maps;
  blank_maps.reserve(c.images.size());
  const std::vector<unsigned char> passes = pass_record_bytes(r.pass_hashes);
  for (const std::string& image : c.images) {
    const fs::path target = bless_target(suite, c, image, platform, tag);
    writes.emplace_back(target, images.bytes.at(image));
    written += (written.empty() ? "" : ", ") + writes.back().first.string();
    // Always for a rendered case, even empty: an older record must not outlive its golden.
    if (!c.source) writes.emplace_back(pass_record(target), passes);
    // Regions need a map beside the golden: a black one (every pixel unpainted) to paint,
    // never over one that exists.
    const fs::path map = region_map(target, image);
    if (!c.tolerance.regions.empty() && !fs::exists(map)) {
      const ImageSize size = decode_picture(images.bytes.at(image), target.string()).size();
      RgbaImage black(size.width, size.height);
      for (std::size_t i = 3; i < black.view().bytes(); i += 4) black.data()[i] = 255;
      blank_maps.push_back(encode_png_rgba8(black, 6));
      writes.emplace_back(map, blank_maps.back());
      written += ", " + map.string();
    }
  }
  remove_stale_temporaries(dir);
  try {
    // Folder mode's one expected file is replaced by one rename; a suite case's folder whole.
    if (c.source && !c.source->golden_file.empty()) {
      refuse_links_below(suite.goldens, c.source->golden_file);
      replace_goldens(writes);
    } else {
      replace_case_goldens(dir, writes);
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("goldens not written: ") + e.what());
  }
  r.status = Status::kPass;
  r.message = "wrote " + written;
}

// Folder mode: accepting a deleted image removes the expected file.
void accept_deletion(const Suite& suite, const Case& c, CaseResult& r) {
  refuse_links_below(suite.goldens, c.source->golden_file);
  std::error_code ec;
  if (!fs::remove(c.source->golden_file, ec) && ec) {
    throw std::runtime_error(c.source->golden_file.string() + ": cannot remove: " + ec.message());
  }
  r.status = Status::kPass;
  r.message = "removed " + c.source->golden_file.string();
}

// What was reviewed is what is approved: each image must be the file the report's results.json
// recorded (a later or killed run may have replaced it), and a file, not a link to anything
// outside the report. Throws saying the goldens are untouched.
void read_reviewed_images(const fs::path& report_dir, const Case& c, const CaseResult& reported,
                          CaseImages& images) {
  if (reported.images_left_out) {
    throw std::runtime_error(
        "it passed and its images were left out of the report (--report-images failures); "
        "its goldens are untouched");
  }
  for (const std::string& image : c.images) {
    const fs::path f = report_dir / "cases" / c.id / (image + ext_of(c, image));
    try {
      std::error_code ec;
      if (!fs::is_regular_file(fs::symlink_status(f, ec)))
        throw FileError(f.string() + ": not a regular file");
      images.bytes[image] = read_regular_file(f);
      const auto recorded = reported.image_hashes.find(image);
      if (recorded == reported.image_hashes.end() ||
          recorded->second != bytes_hash(images.bytes[image])) {
        throw FileError(f.string() +
                        ": not the image the report judged (replaced since; check again)");
      }
      if (ext_of(c, image) == ".png") check_png(images.bytes[image], f.string());
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("the report's image is unusable: ") + e.what() +
                               "; its goldens are untouched");
    }
  }
}

// A passing case is left alone: bless never rewrites its goldens unless asked (--force), but it
// does write a platform golden or variant that does not exist yet.
bool passes_already(const Suite& suite, const Case& c, const BlessOptions& b,
                    const std::string& platform, const std::string& judge_platform,
                    const CaseResult& r, CaseImages& images) {
  for (const std::string& image : c.images) {
    if (!fs::exists(bless_target(suite, c, image, platform, b.tag))) return false;
  }
  CaseResult verdict = r;
  try {
    judge_case(suite, c, judge_platform, b.run, std::nullopt, verdict, images);
  } catch (const std::exception&) {
    return false;  // whatever is wrong there, bless replaces it
  }
  return verdict.status == Status::kPass;
}

}  // namespace

RunResults bless(const Suite& suite, const BlessOptions& b) {
  if (!b.tag.empty() && !valid_name(b.tag)) {
    throw std::invalid_argument(
        "--variant '" + printable(b.tag) +
        "' must be letters, digits, - _ . and not start with '.' (it names a file)");
  }
  const bool from_report = b.from_report || b.failed;
  std::vector<const Case*> cases;
  std::map<std::string, CaseResult> reported;
  std::string report_platform;  // the platform the report's images were made on
  if (from_report) {
    const RunResults last = read_results(b.run.report_dir);
    report_platform = last.platform;
    if (last.suite != suite.name) {
      throw std::invalid_argument(printable(
          fmt::format("{}: a report of suite '{}', not '{}'",
                      (b.run.report_dir / "results.json").string(), last.suite, suite.name)));
    }
    for (const CaseResult& c : last.cases) reported[c.id] = c;
    if (b.failed) {
      for (const Case* c : select(suite, b.run.selection)) {
        const auto it = reported.find(c->id);
        if (it != reported.end() && awaits_approval(it->second.status)) {
          cases.push_back(c);
        }
      }
      if (cases.empty()) {
        RunResults none;
        none.suite = suite.name, none.suite_file = absolute_path(suite.file);
        none.expected_folder = suite.expected.empty() ? "" : absolute_path(suite.expected);
        return none;
      }
    }
  }
  if (cases.empty()) cases = select_some(suite, b.run.selection);
  Makers first;
  RunResults run = start_run(suite, b.run, cases, !from_report, first);
  if (from_report && run.platform.empty()) run.platform = report_platform;
  if (b.platform && run.platform.empty()) {
    throw std::invalid_argument(
        "--platform: no platform key (these cases render no scene): set AOSUITE_PLATFORM");
  }
  const std::string environment = run.environment;
  const std::string platform = b.platform ? run.platform : std::string();
  const std::string judge_platform = run.platform;
  const Cache cache = from_report ? Cache() : load_cache(b.run.report_dir);
  run.cases = for_each_case(
      cases, b.run, std::move(first), [&](Makers& makers, const Case& c, CaseResult& r) {
        const bool deleted = c.source && c.source->deleted;
        CaseImages images;
        if (from_report) {
          const auto it = reported.find(c.id);
          if (it == reported.end()) {
            throw std::runtime_error("not in the report " + b.run.report_dir.string() +
                                     " (check it first); its goldens are untouched");
          }
          const Status was = it->second.status;
          if ((was == Status::kPass || was == Status::kFlaky) && !b.force) {
            r.status = Status::kPass, r.kept = true;
            r.message = "passed in the report; goldens kept (--force rewrites them)";
            return;
          }
          if (was == Status::kError) {
            throw std::runtime_error("could not be judged in the report (" + it->second.message +
                                     "); its goldens are untouched");
          }
          if (!deleted) read_reviewed_images(b.run.report_dir, c, it->second, images);
          r.pass_hashes = it->second.pass_hashes;
        } else if (!deleted) {
          try {
            prepare_images(makers, environment, c, b.run, cache, r, images);
          } catch (const std::exception& e) {
            throw std::runtime_error(std::string("could not be rendered: ") + e.what() +
                                     "; its goldens are untouched");
          }
          if (!b.force && passes_already(suite, c, b, platform, judge_platform, r, images)) {
            r.status = Status::kPass, r.kept = true;
            r.message = "passes; goldens kept (--force rewrites them)";
            return;
          }
        }
        if (deleted) {
          accept_deletion(suite, c, r);
        } else {
          write_case_goldens(suite, c, platform, b.tag, images, r);
        }
      });
  return run;
}

}  // namespace aosuite::harness
