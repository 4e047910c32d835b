// The compute pipeline (issue 44) against the fragment one, on llvmpipe: every screen-space
// technique of the registry, each estimator dispatched instead of drawn, must give the same
// AO and images. Both shaders include the same estimator (NAME.glsl) and differ only in where
// the pixel comes from, so on one device they compute the same floats in the same order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "renderer/frame.hpp"
#include "renderer/params.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene.hpp"

namespace aosuite::renderer {
namespace {

Renderer& shared_renderer() {
  static Renderer r;
  return r;
}

// Every registered technique with a compute pass: a new one is compared here with no edit.
std::vector<const TechniqueInfo*> compute_techniques() {
  std::vector<const TechniqueInfo*> out;
  for (const TechniqueInfo& t : techniques())
    if (t.make_compute_pass) out.push_back(&t);
  return out;
}

Images render(const Scene& scene, std::size_t view, RenderSettings s, Pipeline pipeline) {
  s.pipeline = pipeline;
  Images img = shared_renderer().render(scene, scene.views.at(view), s);
  EXPECT_EQ(img.pipeline, pipeline);
  return img;
}

// The number of bytes in which two images of the same size and type differ (0: identical);
// -1 when their sizes or types differ.
long differing_bytes(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return -1;
  const auto bytes = static_cast<std::size_t>(a.total() * a.elemSize());
  long n = 0;
  for (std::size_t i = 0; i < bytes; ++i) n += a.data[i] != b.data[i];
  return n;
}

// Every technique at sizes that are not multiples of the 8x8 workgroup (1x1, 7x5, 321x181: the
// dispatch's spare invocations must write nothing), on a scene of creases and on the village,
// unblurred (the estimator alone) and with the technique's default bilateral blur (the shared
// blur and blend after it). The bound is 0 for every technique: byte-identical float AO and
// 8-bit images, which is what llvmpipe gives (it compiles both stages with the same code
// generator and no fast-math difference between them). A GPU may contract or reorder
// differently per stage; this test is llvmpipe's.
TEST(ComputePipeline, SameAoAndImagesAsFragment) {
  const std::pair<const char*, std::size_t> views[] = {{"corner", 1}, {"village", 0}};
  const std::pair<int, int> sizes[] = {{1, 1}, {7, 5}, {321, 181}};
  for (const TechniqueInfo* t : compute_techniques()) {
    for (const auto& [name, view] : views) {
      const Scene scene = builtin_scene(name);
      for (const auto& [w, h] : sizes) {
        for (Blur blur : {Blur::kNone, default_params(t->id).blur}) {
          RenderSettings s;
          s.width = w, s.height = h, s.technique = t->id, s.params = default_params(t->id);
          s.params.blur = blur;
          const std::string what = std::string(t->name) + " " + name + " " + std::to_string(w) +
                                   "x" + std::to_string(h) + " blur " +
                                   std::string(blur_name(blur));
          const Images fragment = render(scene, view, s, Pipeline::kFragment);
          const Images compute = render(scene, view, s, Pipeline::kCompute);
          EXPECT_EQ(differing_bytes(fragment.ao, compute.ao), 0) << what << ": float AO";
          EXPECT_EQ(differing_bytes(fragment.no_ao, compute.no_ao), 0) << what << ": no AO";
          EXPECT_EQ(differing_bytes(fragment.with_ao, compute.with_ao), 0) << what << ": with AO";
          EXPECT_EQ(differing_bytes(fragment.ao_only, compute.ao_only), 0) << what << ": AO only";
        }
      }
    }
  }
}

// At 1921x1081 (one past the 1080p frame in each direction) on the village with the default
// blur: the size the benchmarks time. GTAO, the first technique ported, and MSSAO, whose five
// levels are five odd sizes; all six took 24 s on llvmpipe, these two a third of it.
TEST(ComputePipeline, SameImagesOneOverFullHd) {
  const Scene village = builtin_scene("village");
  for (Technique t : {Technique::kGtao, Technique::kMssao}) {
    RenderSettings s;
    s.width = 1921, s.height = 1081, s.technique = t, s.params = default_params(t);
    s.outputs = parse_outputs("with_ao,ao_float");
    const Images fragment = render(village, 0, s, Pipeline::kFragment);
    const Images compute = render(village, 0, s, Pipeline::kCompute);
    EXPECT_EQ(differing_bytes(fragment.ao, compute.ao), 0) << technique_name(t) << ": float AO";
    EXPECT_EQ(differing_bytes(fragment.with_ao, compute.with_ao), 0)
        << technique_name(t) << ": with AO";
  }
}

// dispatch_rows interleaves the rows of workgroups over the device's shares of a dispatch, one
// per llvmpipe thread, and each invocation of the blend shades light_pass_rows() pixels, 8 rows
// apart (ctest runs this test once more with LP_NUM_THREADS=3 and once with
// AOSUITE_PIXEL_ROWS=1). Whatever their counts, every pixel must be shaded once: at sizes whose
// rows of workgroups (1, 1, 2 and 25 at one pixel an invocation; 1, 1, 1 and 13 at two) are
// mostly no multiple of 2 or 3, and whose last workgroup's second pixels fall partly inside the
// image (13 rows) or outside it (the others), each technique's compute AO and images equal the
// fragment ones. A render at another size comes between, so the compute pipeline writes into
// fresh images, where a pixel it skipped would stay 0 and differ.
TEST(ComputePipeline, EveryPixelIsWrittenWhateverTheShares) {
  Renderer& renderer = shared_renderer();
  const char* threads = std::getenv("LP_NUM_THREADS");
  const int expected = threads && *threads ? std::atoi(threads)
                                           : static_cast<int>(std::thread::hardware_concurrency());
  EXPECT_EQ(dispatch_shares(), std::max(expected, 1)) << "llvmpipe's compute threads";
  const char* rows = std::getenv("AOSUITE_PIXEL_ROWS");
  EXPECT_EQ(light_pass_rows(), rows && *rows ? std::atoi(rows) : 2) << "pixels an invocation";
  const Scene village = builtin_scene("village");
  for (const TechniqueInfo* t : compute_techniques()) {
    for (const auto& [w, h] :
         {std::pair{1, 1}, std::pair{7, 5}, std::pair{9, 13}, std::pair{321, 199}}) {
      RenderSettings s;
      s.width = w, s.height = h, s.technique = t->id, s.params = default_params(t->id);
      const Images fragment = render(village, 0, s, Pipeline::kFragment);
      RenderSettings other = s;
      other.width = w + 1;
      renderer.render(village, village.views[0], other);
      const Images compute = render(village, 0, s, Pipeline::kCompute);
      const std::string what = std::string(t->name) + " " + std::to_string(w) + "x" +
                               std::to_string(h) + ", " + std::to_string(dispatch_shares()) +
                               " shares, " + std::to_string(light_pass_rows()) + " rows";
      EXPECT_EQ(differing_bytes(fragment.ao, compute.ao), 0) << what << ": float AO";
      EXPECT_EQ(differing_bytes(fragment.with_ao, compute.with_ao), 0) << what << ": with AO";
    }
  }
}

// At half resolution (half_res=1) the downsample, the technique's pass on the half-size
// G-buffer and the upsample are each drawn or dispatched, so the two pipelines must agree there
// too: at sizes whose halves are odd or 1x1 (7x5 -> 4x3, 1x1 -> 1x1, 321x181 -> 161x91).
TEST(ComputePipeline, SameAoAtHalfResolution) {
  const Scene corner = builtin_scene("corner");
  for (const TechniqueInfo* t : compute_techniques()) {
    for (const auto& [w, h] : {std::pair{1, 1}, std::pair{7, 5}, std::pair{321, 181}}) {
      RenderSettings s;
      s.width = w, s.height = h, s.technique = t->id, s.params = default_params(t->id);
      s.params.half_res = 1;
      s.outputs = parse_outputs("with_ao,ao_float");
      const Images fragment = render(corner, 1, s, Pipeline::kFragment);
      const Images compute = render(corner, 1, s, Pipeline::kCompute);
      const std::string what = std::string(t->name) + " " + std::to_string(w) + "x" +
                               std::to_string(h) + " at half resolution";
      EXPECT_EQ(differing_bytes(fragment.ao, compute.ao), 0) << what << ": float AO";
      EXPECT_EQ(differing_bytes(fragment.with_ao, compute.with_ao), 0) << what << ": with AO";
    }
  }
}

// PMI is drawn over the scene in both pipelines (object space); its blend is the compute one.
TEST(ComputePipeline, ObjectSpaceTechniqueRendersInBoth) {
  const Scene corner = builtin_scene("corner");
  RenderSettings s;
  s.width = 64, s.height = 48, s.technique = Technique::kPmi;
  s.params = default_params(Technique::kPmi);
  s.params.pmi.viewpoints = 42, s.params.pmi.resolution = 160;
  const Images fragment = render(corner, 1, s, Pipeline::kFragment);
  const Images compute = render(corner, 1, s, Pipeline::kCompute);
  EXPECT_EQ(differing_bytes(fragment.ao, compute.ao), 0);
  EXPECT_EQ(differing_bytes(fragment.with_ao, compute.with_ao), 0);
}

// llvmpipe silently ends a shader invocation's loops after 65,535 iterations, all its loops
// counted together (bench/README.md). params.cpp's ranges keep a pixel's loops under that, so
// each loop count a technique reads (samples, slices, steps) at the top of its range must give
// all its taps: close to half the count (a loop cut short would leave occlusion out where the
// street is dark), and the same in both pipelines, whose loops are the same.
TEST(ComputePipeline, LoopsAtTheTopOfTheirRangesRunToTheEnd) {
  const Scene village = builtin_scene("village");
  for (const TechniqueInfo* t : compute_techniques()) {
    RenderSettings most, half;
    most.width = half.width = 64, most.height = half.height = 36;
    most.technique = half.technique = t->id;
    most.params = half.params = default_params(t->id);
    for (const char* key : {"samples", "slices", "steps"}) {
      const ParamSpec& spec = param_spec(key);
      if (!applies(spec, t->id)) continue;
      const int top = static_cast<int>(spec.max);
      set_param(most.params, key, std::to_string(top));
      set_param(half.params, key, std::to_string(top / 2));
    }
    const Images fragment = render(village, 0, most, Pipeline::kFragment);
    const Images compute = render(village, 0, most, Pipeline::kCompute);
    const Images fewer = render(village, 0, half, Pipeline::kCompute);
    EXPECT_EQ(differing_bytes(fragment.ao, compute.ao), 0) << t->name;
    const double rmse = cv::norm(compute.ao, fewer.ao, cv::NORM_L2) / std::sqrt(compute.ao.total());
    EXPECT_LT(rmse, 0.01) << t->name << ": the top of the range against half of it";
  }
}

TEST(ComputePipeline, EveryScreenSpaceTechniqueHasBoth) {
  for (const TechniqueInfo& t : techniques()) {
    const bool screen = t.space == Space::kScreen;
    EXPECT_EQ(t.make_fragment_pass != nullptr, screen) << t.name;
    EXPECT_EQ(t.make_compute_pass != nullptr, screen) << t.name;
  }
}

TEST(ComputePipeline, NamesParseBack) {
  for (Pipeline p : {Pipeline::kFragment, Pipeline::kCompute})
    EXPECT_EQ(parse_pipeline(pipeline_name(p)), p);
  EXPECT_THROW(parse_pipeline("vertex"), std::invalid_argument);
}

// The default suite's goldens are the fragment pipeline's: llvmpipe keeps it by default.
TEST(ComputePipeline, FragmentIsTheDefaultOnLlvmpipe) {
  EXPECT_EQ(shared_renderer().default_pipeline(), Pipeline::kFragment);
  const Scene corner = builtin_scene("corner");
  RenderSettings s;
  s.width = 8, s.height = 8;
  EXPECT_EQ(shared_renderer().render(corner, corner.views[0], s).pipeline, Pipeline::kFragment);
}

}  // namespace
}  // namespace aosuite::renderer
