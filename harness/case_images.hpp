// Making a case's images in the report folder: rendered by its kind, written by its command, read
// from its files, or reused unchanged from the last run there. What check and bless share.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "harness/case_kind.hpp"
#include "harness/results.hpp"
#include "harness/reuse_cache.hpp"
#include "harness/runner.hpp"
#include "image/rgba_image.hpp"

namespace aosuite::harness {

// How a suite allows links out of its folders (check_no_link_out's message).
inline constexpr std::string_view kFollowLinks = "`follow_links = true` in the suite allows it";

// One thread's makers, one per kind, each made when a case of its kind first needs it (a GL
// context costs time and memory: an image-only run makes none).
struct Makers {
  std::map<const CaseKind*, std::unique_ptr<Maker>> by_kind;
  Maker& get(const CaseKind* kind) {
    std::unique_ptr<Maker>& m = by_kind[kind];
    if (!m) m = kind->maker(nullptr);
    return *m;
  }
};

// The file type of a case's image: an image case's own (".png", folder mode's ".exr"), else
// what its kind says.
std::string ext_of(const Case& c, std::string_view image);
// The images a case keeps in its report folder: an image case's own, else its kind's.
std::vector<std::string> kept_images(const Case& c);

// A case's image as Resemble sees it, 8-bit RGBA, decoded once; empty for a float (linear)
// image, which only the metrics judge.
const RgbaImage& decoded_pixels(CaseImages& images, const Case& c, const std::string& name,
                                const std::filesystem::path& case_dir);

// The result a case starts from: its id, kind, labels, source, params and image files.
CaseResult result_skeleton(const Case& c);

// Renders, runs or reads (or reuses) one case into the report folder. Returns the previous
// result when the images were reused.
std::optional<CaseResult> prepare_images(Makers& makers, const std::string& environment,
                                         const Case& c, const RunOptions& o, const Cache& cache,
                                         CaseResult& r, CaseImages& images);

}  // namespace aosuite::harness
