// One rendered suite case's own part (harness::MadeCase): scene, view, technique, parameters;
// what its images depend on and what the report says of it.
#pragma once

#include <array>
#include <memory>
#include <string>

#include "harness/case_kind.hpp"
#include "renderer/params.hpp"
#include "renderer/scene/scene.hpp"
#include "renderer/technique.hpp"

namespace aosuite::ao {

// The images of a rendered case that can be gated. ao_float is the AO term as float EXR
// (ao_float.exr), rendered only for cases that gate it, by metric gates only.
inline constexpr std::array<const char*, 4> kImageNames{"no_ao", "with_ao", "ao_only", "ao_float"};
// The file type of a render's image: ".exr" for ao_float, else ".png".
std::string render_ext(std::string_view image);

struct SceneCase final : harness::MadeCase {
  std::shared_ptr<const renderer::Scene> scene;
  std::string view;
  renderer::Technique technique{};
  renderer::AoParams params;
  bool allow_empty = false;  // the suite expects the view to draw no geometry

  // The renderer's build (the bytes of the library holding this code), every shader's text as
  // the renderer will read it, the scene's geometry, colours and views, the view, technique,
  // parameters, size and the GL implementation.
  std::string input_hash(const harness::Case& c, const std::string& environment) const override;
  std::vector<std::string> kept_images(const harness::Case& c) const override;
  std::string ext(std::string_view image) const override { return render_ext(image); }
  void describe(const harness::Case& c, harness::CaseResult& r) const override;
};

}  // namespace aosuite::ao
