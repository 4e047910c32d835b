// The pipeline: scene -> G-buffer -> AO -> blur -> blend -> images, with per-pass times.
#pragma once

#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "renderer/frame.hpp"
#include "renderer/pmi/pmi_channel.hpp"
#include "renderer/technique.hpp"

namespace aosuite::renderer {

// Which images the caller wants; passes nobody needs are not run.
struct Outputs {
  bool no_ao = true, with_ao = true, ao_only = true, ao_float = true;
  bool normal = false;  // the G-buffer normal (for the ray-traced reference); never by "all"
  // Each pass's output read back and hashed (Images::pass_hashes): what a failing case's first
  // differing pass is found from. Costs a read-back between AO and blur; never by "all".
  bool pass_hashes = false;
  bool needs_ao() const { return with_ao || ao_only || ao_float; }
};
Outputs parse_outputs(const std::string& csv);  // e.g. "no_ao,ao_float"; "all"

struct RenderSettings {
  int width = 1920, height = 1080;
  Technique technique = Technique::kAlchemy;
  AoParams params = default_params(Technique::kAlchemy);
  Outputs outputs;
  // Fragment draws or compute dispatches for the screen-space passes; unset: the device's
  // default (Renderer::default_pipeline). The images are the same either way.
  std::optional<Pipeline> pipeline;
  GBufferKind gbuffer = GBufferKind::kFull;
};

// The depth and view-space normal alone, no AO and no images: the G-buffer a ray-traced
// reference is traced over.
RenderSettings gbuffer_settings(int width, int height);

struct Images {
  cv::Mat no_ao, with_ao, ao_only;  // CV_8UC4 RGBA, sRGB, top row first
  cv::Mat ao;                       // CV_32F visibility in [0, 1]; 1 on background
  cv::Mat depth;                    // CV_32F linear view depth; 0 on background
  // Pixels that drew geometry: 0 when the view sees none (all clipped, or all background),
  // which callers must not pass off as a frame (render warns, a suite case fails).
  int geometry_pixels = 0;
  cv::Mat normal;               // CV_32FC3 view-space unit normal (x, y, z); Outputs::normal
  std::vector<PassTime> times;  // each pass's GPU time
  double frame_ms = 0;          // wall time from the first pass's submission to the last one's end
  Pipeline pipeline = Pipeline::kFragment;  // the one that ran
  // Outputs::pass_hashes: each pass that ran and the content hash of what it wrote, in pipeline
  // order: gbuffer (depth, normal, albedo), ao (before the blur), blur, blend (the images).
  std::vector<std::pair<std::string, std::string>> pass_hashes;
};

class Renderer {
 public:
  // Makes a GL 4.5 core context as gl_choice() says (EGL or OSMesa); throws
  // std::runtime_error if none can be made.
  Renderer();
  ~Renderer();
  std::string gl_description() const;  // "vendor | renderer | version"
  std::string gl_source() const;       // the backend and device, e.g. "EGL device 0 (software)"
  // The pipeline a frame runs when its settings name none: the faster one on this device where
  // it was measured (bench/README.md).
  Pipeline default_pipeline() const;
  // `pmi_override`: for Technique::kPmi, draw these maps' per-vertex values instead of the
  // scene's own PMI (how `aosuite pmi-study` shows ray-traced per-vertex AO the same way).
  Images render(const Scene& scene, const View& view, const RenderSettings& settings,
                const PmiMaps* pmi_override = nullptr);
  // PMI's view-independent channel and maps, computed once per scene content and settings while
  // the cache's memory budget holds them (PmiCache; what Technique::kPmi renders;
  // `aosuite viewpoints` reads the per-view values).
  std::shared_ptr<const PmiMaps> pmi_maps(const Scene& scene, const PmiSettings& settings);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace aosuite::renderer
