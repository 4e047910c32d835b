#include "ao/scene_maker.hpp"

#include <fmt/format.h>

#include "ao/scene_case.hpp"
#include "common/file_io.hpp"
#include "compare/opencv.hpp"
#include "harness/goldens.hpp"
#include "image/exr_file.hpp"
#include "image/image_io.hpp"
#include "renderer/renderer.hpp"

namespace aosuite::ao {
namespace {

namespace fs = std::filesystem;
namespace rd = aosuite::renderer;

double raw_mismatch(const cv::Mat& a, const cv::Mat& b, resemble::Mode mode) {
  resemble::Options o;
  o.modes = {mode};
  return resemble::compare(a, b, o).raw_mismatch_percentage;
}

class SceneMaker final : public harness::Maker {
 public:
  explicit SceneMaker(harness::Environment* env) {
    if (!env) return;
    // The backend and device after the driver's own three fields: the report names them, and
    // platform_key reads the renderer field alone, so goldens match on EGL and OSMesa alike.
    env->description = renderer_.gl_description() + " | " + renderer_.gl_source();
    env->platform = harness::platform_key(env->description);
  }

  void make(const harness::Case& c, const fs::path& case_dir, harness::CaseResult& r,
            harness::CaseImages& out) override {
    const auto& sc = static_cast<const SceneCase&>(*c.made);
    rd::RenderSettings s;
    s.width = c.width, s.height = c.height, s.technique = sc.technique, s.params = sc.params;
    const bool ao_float = std::ranges::count(c.images, "ao_float") > 0;
    s.outputs = {
        .no_ao = true, .with_ao = true, .ao_only = true, .ao_float = ao_float, .pass_hashes = true};
    const rd::View& view = rd::find_view(*sc.scene, sc.view);
    rd::Images img = renderer_.render(*sc.scene, view, s);
    // An empty frame is never a silent pass: its golden would be an image of the background.
    if (img.geometry_pixels == 0 && !sc.allow_empty) {
      throw std::runtime_error(fmt::format(
          "view '{}' draws no geometry (everything clipped or background; near plane {:g}); "
          "if that is expected, say allow_empty = true",
          sc.view, view.near));
    }
    fs::create_directories(case_dir);
    for (const auto& [name, mat] :
         {std::pair{"no_ao", &img.no_ao}, {"with_ao", &img.with_ao}, {"ao_only", &img.ao_only}}) {
      out.rgba[name] = copy_of(view_of(*mat));
      out.bytes[name] = encode_png_rgba8(out.rgba[name], 6);
      harness::keep_in_report(case_dir / (std::string(name) + ".png"), out.bytes[name]);
    }
    if (c.tolerance.foreground_only) {
      // Geometry where the G-buffer has depth: white; sky black. Kept, so a reused render has it.
      cv::Mat mask(img.depth.size(), CV_8UC4, cv::Scalar(0, 0, 0, 255));
      mask.setTo(cv::Scalar(255, 255, 255, 255), img.depth > 0);
      out.bytes["foreground"] = encode_png_rgba8(mask, 6);
      harness::keep_in_report(case_dir / "foreground.png", out.bytes["foreground"]);
    }
    if (ao_float) {
      const fs::path exr = case_dir / "ao_float.exr";
      write_exr(exr, img.ao.cols, img.ao.rows, img.ao.ptr<float>());
      out.bytes["ao_float"] = read_file(exr);
    }
    for (const rd::PassTime& t : img.times) r.times.push_back({t.pass + " (GPU)", t.gpu_ms});
    r.pass_hashes = img.pass_hashes;
    // How much of the picture AO changes (the thesis's Tables 11-14).
    r.figures["ao_effect_less"] = raw_mismatch(img.no_ao, img.with_ao, resemble::Mode::kLess);
    r.figures["ao_effect_nothing"] = raw_mismatch(img.no_ao, img.with_ao, resemble::Mode::kNothing);
  }

 private:
  rd::Renderer renderer_;
};

}  // namespace

std::unique_ptr<harness::Maker> make_scene_maker(harness::Environment* env) {
  return std::make_unique<SceneMaker>(env);
}

}  // namespace aosuite::ao
