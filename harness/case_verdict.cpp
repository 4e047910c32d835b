#include "harness/case_verdict.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "common/file_io.hpp"
#include "harness/case_hash.hpp"
#include "harness/case_images.hpp"
#include "harness/escape.hpp"
#include "harness/goldens.hpp"
#include "harness/report_images.hpp"
#include "image/image_io.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

void refuse_links_below(const fs::path& root, const fs::path& file) {
  fs::path at = root;
  for (const fs::path& part : file.lexically_relative(root)) {
    at /= part;
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(at, ec))) {
      throw std::runtime_error(at.string() + ": a symbolic link; nothing is written through it");
    }
  }
}

fs::path bless_target(const Suite& suite, const Case& c, const std::string& image,
                      const std::string& platform, const std::string& tag) {
  if (c.source && !c.source->golden_file.empty()) return c.source->golden_file;
  return golden_path(suite.goldens / c.id, image, ext_of(c, image), platform, tag);
}

namespace {

// The goldens accepted for one image: folder mode's one expected file, else the goldens folder.
std::vector<fs::path> goldens_of(const Suite& suite, const Case& c, const std::string& image,
                                 const std::string& platform) {
  if (c.source && !c.source->golden_file.empty()) {
    refuse_links_below(suite.goldens, c.source->golden_file);
    std::error_code ec;
    if (fs::exists(fs::symlink_status(c.source->golden_file, ec))) return {c.source->golden_file};
    return {};
  }
  std::vector<fs::path> found =
      accepted_goldens(suite.goldens / c.id, image, ext_of(c, image), platform);
  if (!suite.follow_links) {
    for (const fs::path& g : found) check_no_link_out(g, suite.goldens, kFollowLinks);
  }
  return found;
}

// foreground_only's pixels: the kept mask's white ones.
std::optional<Counted> foreground(const Case& c, CaseImages& images, const fs::path& case_dir) {
  if (!c.tolerance.foreground_only) return std::nullopt;
  const RgbaImage& mask = decoded_pixels(images, c, "foreground", case_dir);
  Counted out(std::size_t(mask.width()) * std::size_t(mask.height()));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = mask.data()[4 * i] != 0;
  return out;
}

}  // namespace

void judge_case(const Suite& suite, const Case& c, const std::string& platform, const RunOptions& o,
                const std::optional<CaseResult>& prev, CaseResult& r, CaseImages& images) {
  const fs::path case_dir = o.report_dir / "cases" / c.id;
  std::vector<std::vector<ReadGolden>> goldens;
  for (const std::string& image : c.images)
    goldens.push_back(read_goldens(goldens_of(suite, c, image, platform)));
  r.judge_hash = judge_hash(c, r.input_hash, goldens);
  if (prev && prev->judge_hash == r.judge_hash && prev->status != Status::kError) {
    const double seconds = r.seconds;
    r = *prev;
    r.reused = true, r.seconds = seconds, r.attempts = 1;
    if (r.status == Status::kFlaky) {  // this run passed at once: the old attempts are not its
      r.status = Status::kPass, r.message.clear();
      r.failed_attempts.clear();
    }
    return;
  }
  r.status = Status::kPass;
  const std::optional<Counted> counted = foreground(c, images, case_dir);
  for (std::size_t i = 0; i < c.images.size(); ++i) {
    const std::string& name = c.images[i];
    const std::string ext = ext_of(c, name);
    ImageVerdict v = judge(name, images.bytes.at(name), goldens[i], c.tolerance, true,
                           counted ? &*counted : nullptr);
    if (v.status == Status::kNew)
      v.message += " at " + printable(bless_target(suite, c, name, "", "").string());
    const bool show = v.status == Status::kFail || v.status == Status::kWarn || o.diff_all;
    if (!v.diff.empty() && show) {
      write_png_rgba8(case_dir / ("diff_" + name + ".png"), v.diff);
      r.files["diff:" + name] = c.id + "/diff_" + name + ".png";
    }
    if (v.views && show) {
      write_png_rgba8(case_dir / ("abs_" + name + ".png"), v.views->absolute);
      write_png_rgba8(case_dir / ("signed_" + name + ".png"), v.views->signed_change);
      r.files["abs:" + name] = c.id + "/abs_" + name + ".png";
      r.files["signed:" + name] = c.id + "/signed_" + name + ".png";
    }
    if (!v.heatmap.empty() && show) {
      write_png_rgba8(case_dir / ("heat_" + name + ".png"), v.heatmap);
      r.files["heat:" + name] = c.id + "/heat_" + name + ".png";
    }
    if (show && !v.ignored.empty()) {  // what the tolerance ignored, drawn over the diff
      write_png_rgba8(case_dir / ("ignored_" + name + ".png"),
                      ignored_overlay(v.ignored, v.diff.width(), v.diff.height()));
      r.files["ignored:" + name] = c.id + "/ignored_" + name + ".png";
    }
    if (!c.tolerance.regions.empty() && !v.golden.empty()) {
      const fs::path map = region_map(v.golden, name);
      if (fs::is_regular_file(map)) {
        keep_in_report(case_dir / ("regions_" + name + ".png"), read_regular_file(map));
        r.files["regions:" + name] = c.id + "/regions_" + name + ".png";
      }
    }
    if (!v.identical && !v.golden.empty() && v.status != Status::kError) {
      // A copy written under a temporary name and renamed: never a truncated golden image in
      // the report, even on a full disk.
      // The bytes judged, not the file as it is now.
      const auto judged = std::ranges::find(goldens[i], v.golden, &ReadGolden::file);
      keep_in_report(case_dir / ("golden_" + name + ext),
                     judged != goldens[i].end() ? judged->bytes : read_regular_file(v.golden));
      r.files["golden:" + name] = c.id + "/golden_" + name + ext;
    } else if (v.identical) {
      r.files["golden:" + name] = c.id + "/" + name + ext;
    }
    if ((v.status == Status::kFail || v.status == Status::kWarn) && !r.pass_hashes.empty()) {
      const std::string first = first_differing_pass(read_pass_record(v.golden), r.pass_hashes);
      if (!first.empty()) v.message += "; " + first;
    }
    if (r.message.empty() && v.status != Status::kPass) r.message = name + ": " + v.message;
    r.status = worst(r.status, v.status);
    v.diff = {}, v.heatmap = {};
    r.images.push_back(std::move(v));
  }
}

void judge_deleted(const Case& c, const RunOptions& o, CaseResult& r) {
  const fs::path case_dir = o.report_dir / "cases" / c.id;
  fs::create_directories(case_dir);
  r.files.clear();
  const std::string ext = ext_of(c, "image");
  keep_in_report(case_dir / ("golden_image" + ext), read_regular_file(c.source->golden_file));
  r.files["golden:image"] = c.id + "/golden_image" + ext;
  r.status = Status::kFail, r.deleted = true;
  r.message = "deleted: only in the expected folder";
  ImageVerdict v;
  v.image = "image", v.status = Status::kFail, v.golden = c.source->golden_file;
  v.mismatch_percent = 100, v.mismatch_text = "100.00", v.message = r.message;
  r.images.push_back(std::move(v));
}

}  // namespace aosuite::harness
