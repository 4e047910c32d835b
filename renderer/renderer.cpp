#include "renderer/renderer.hpp"

#include <chrono>
#include <cmath>
#include <span>
#include <sstream>
#include <stdexcept>

#include "common/content_hash.hpp"
#include "renderer/gl/gl_context.hpp"
#include "renderer/params.hpp"
#include "renderer/passes/ao_pass.hpp"
#include "renderer/passes/blend_pass.hpp"
#include "renderer/passes/blur_pass.hpp"
#include "renderer/passes/gbuffer_pass.hpp"
#include "renderer/passes/half_res_pass.hpp"
#include "renderer/pmi/pmi_cache.hpp"
#include "renderer/pmi/pmi_pass.hpp"
#include "renderer/pmi/viewpoint_sphere.hpp"
#include "renderer/scene/view_check.hpp"

namespace aosuite::renderer {

RenderSettings gbuffer_settings(int width, int height) {
  RenderSettings s;
  s.width = width, s.height = height;
  s.outputs = Outputs{false, false, false, false};
  s.outputs.normal = true;
  return s;
}

Outputs parse_outputs(const std::string& csv) {
  if (csv == "all") return {};
  Outputs o{false, false, false, false};
  std::stringstream ss(csv);
  for (std::string item; std::getline(ss, item, ',');) {
    if (item == "no_ao")
      o.no_ao = true;
    else if (item == "with_ao")
      o.with_ao = true;
    else if (item == "ao_only")
      o.ao_only = true;
    else if (item == "ao_float")
      o.ao_float = true;
    else
      throw std::invalid_argument("unknown output '" + item +
                                  "' (no_ao, with_ao, ao_only, ao_float, all)");
  }
  return o;
}

struct Renderer::State {
  std::unique_ptr<GlContext> context = make_gl_context(gl_choice());
  GBufferPass gbuffer_pass;
  std::unique_ptr<DepthGBufferPass> depth_gbuffer_pass;  // compiled on first use
  // The blur's kernel suits the device: runs of pixels on a CPU rasteriser, shared-memory
  // tiles on a GPU (blur_pass.hpp). Made on first use, when the context can name its device.
  std::unique_ptr<BlurPass> blur_pass;
  // Per pipeline, compiled on first use.
  std::map<Pipeline, std::unique_ptr<BlendPass>> blend_passes;
  std::map<std::pair<Technique, Pipeline>, std::unique_ptr<AoPass>> ao_passes;
  std::map<Pipeline, std::unique_ptr<HalfResPass>> half_res_passes;
  std::unique_ptr<PmiPass> pmi_pass;  // compiled on first use
  PmiCache pmi_cache;
  // Targets, reallocated when the size changes.
  int width = 0, height = 0;
  GBuffer gbuffer;
  Texture ao, no_ao, with_ao, ao_only;
  Framebuffer ao_fb, blend_fb;
  // The AO before the blur, copied on the GPU when pass hashes are asked for, so its read-back
  // happens after the timed frame. Made on first use.
  Texture unblurred_ao;

  void allocate(int w, int h) {
    width = w, height = h;
    gbuffer = make_gbuffer(w, h);
    ao = make_texture(GL_R32F, w, h);
    no_ao = make_texture(GL_RGBA8, w, h);
    with_ao = make_texture(GL_RGBA8, w, h);
    ao_only = make_texture(GL_RGBA8, w, h);
    unblurred_ao = Texture();
    // Full-resolution AO targets share the G-buffer's depth so sky pixels are never shaded.
    ao_fb = make_framebuffer({ao.get()}, gbuffer.zbuffer.get());
    blend_fb = make_framebuffer({no_ao.get(), with_ao.get(), ao_only.get()});
  }

  AoPass& ao_pass(Technique t, Pipeline p) {
    auto& pass = ao_passes[{t, p}];
    if (!pass) pass = make_ao_pass(t, p);
    return *pass;
  }

  HalfResPass& half_res(Pipeline p) {
    auto& pass = half_res_passes[p];
    if (!pass) pass = std::make_unique<HalfResPass>(p);
    return *pass;
  }

  BlurPass& blur(Pipeline device_default) {
    if (!blur_pass) {
      blur_pass = std::make_unique<BlurPass>(
          device_default == Pipeline::kCompute ? BlurKernel::kTiles : BlurKernel::kRuns);
    }
    return *blur_pass;
  }

  const BlendPass& blend_pass(Pipeline p) {
    auto& pass = blend_passes[p];
    if (!pass) pass = std::make_unique<BlendPass>(p);
    return *pass;
  }
};

namespace {

double now_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// GL's rows run bottom to top; images run top to bottom.
cv::Mat read_texture(GLuint tex, int w, int h, GLenum format, GLenum type, int cv_type) {
  cv::Mat m(h, w, cv_type);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(tex, 0, format, type, static_cast<GLsizei>(m.total() * m.elemSize()), m.data);
  check_gl("read back");
  cv::Mat flipped;
  cv::flip(m, flipped, 0);
  return flipped;
}

std::string texels_hash(std::initializer_list<cv::Mat> texels) {
  ContentHash h;
  for (const cv::Mat& m : texels)
    h.add(std::span<const unsigned char>(m.data, m.total() * m.elemSize()));
  return h.hex();
}

void validate(const View& view, const RenderSettings& s) {
  auto fail = [](const std::string& why) { throw std::invalid_argument(why); };
  if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384) {
    fail("resolution " + std::to_string(s.width) + "x" + std::to_string(s.height) +
         " is outside 1..16384 per side");
  }
  check_params(s.params);
  if (object_space(s.technique)) make_icosphere(s.params.pmi.viewpoints);  // a bad count
  if (const auto problem = view_problem(view))  // shared with scene files (view_check.hpp)
    fail("view '" + view.name + "': " + problem->why);
}

}  // namespace

Renderer::Renderer() : state_(std::make_unique<State>()) {}
Renderer::~Renderer() = default;

std::string Renderer::gl_description() const { return state_->context->description(); }
std::string Renderer::gl_source() const { return state_->context->source(); }

// The faster pipeline, as measured (bench/README.md, "both pipelines"): on a GPU (an NVIDIA
// H200) the compute AO passes took 0.07-0.39 ms at 1080p where the drawn ones took 1.9-4.2 ms;
// on Mesa's llvmpipe most compute frames are still 1.07-1.20x as long, its rows of workgroups
// interleaved or not ("Where the threads wait"). The images are the same either way.
Pipeline Renderer::default_pipeline() const {
  const auto* device = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return device && !software_renderer(device) ? Pipeline::kCompute : Pipeline::kFragment;
}

std::shared_ptr<const PmiMaps> Renderer::pmi_maps(const Scene& scene, const PmiSettings& settings) {
  return state_->pmi_cache.get(scene, settings);
}

Images Renderer::render(const Scene& scene, const View& view, const RenderSettings& s,
                        const PmiMaps* pmi_override) {
  validate(view, s);
  State& st = *state_;
  if (s.width != st.width || s.height != st.height) st.allocate(s.width, s.height);
  const Camera camera = make_camera(view, s.width, s.height);
  const Pipeline pipeline = s.pipeline.value_or(default_pipeline());
  const AoTarget ao_target{st.ao_fb.get(), st.ao.get()};
  const GpuScene gpu_scene(scene);
  Images out;
  std::vector<PassTimer> timers;
  glFinish();  // the frame's wall time starts with an idle pipeline
  const double start_ms = now_ms();

  if (s.gbuffer == GBufferKind::kDepth) {
    const float albedo[4] = {0.8f, 0.8f, 0.8f, 1};  // the depth pass has no colour
    glClearTexImage(st.gbuffer.albedo.get(), 0, GL_RGBA, GL_FLOAT, albedo);
    if (!st.depth_gbuffer_pass) st.depth_gbuffer_pass = std::make_unique<DepthGBufferPass>();
    for (PassTimer& t : st.depth_gbuffer_pass->run(gpu_scene, camera, st.gbuffer))
      timers.push_back(std::move(t));
  } else {
    PassTimer gbuffer_timer("gbuffer");
    st.gbuffer_pass.run(gpu_scene, camera, st.gbuffer);
    gbuffer_timer.stop();
    timers.push_back(std::move(gbuffer_timer));
  }

  const bool want_ao = s.outputs.needs_ao();
  if (want_ao) {
    if (object_space(s.technique)) {  // PMI: cached maps drawn over the scene
      const auto cached = pmi_override ? nullptr : pmi_maps(scene, pmi_settings(s.params));
      if (!st.pmi_pass) st.pmi_pass = std::make_unique<PmiPass>();
      timers.push_back(st.pmi_pass->run(scene, pmi_override ? *pmi_override : *cached, camera,
                                        s.params, st.ao_fb.get()));
    } else {
      AoPass& ao_pass = st.ao_pass(s.technique, pipeline);
      if (s.params.half_res) {
        HalfResPass& half = st.half_res(pipeline);
        timers.push_back(half.downsample(st.gbuffer));
        for (PassTimer& t :
             ao_pass.run(half.gbuffer(), half.camera(camera), s.params, half.target()))
          timers.push_back(std::move(t));
        timers.push_back(half.upsample(st.gbuffer, ao_target));
      } else {
        for (PassTimer& t : ao_pass.run(st.gbuffer, camera, s.params, ao_target))
          timers.push_back(std::move(t));
      }
    }
    if (s.outputs.pass_hashes && s.params.blur != Blur::kNone) {  // before the blur overwrites it
      if (st.unblurred_ao.get() == 0) st.unblurred_ao = make_texture(GL_R32F, s.width, s.height);
      glCopyImageSubData(st.ao.get(), GL_TEXTURE_2D, 0, 0, 0, 0, st.unblurred_ao.get(),
                         GL_TEXTURE_2D, 0, 0, 0, 0, s.width, s.height, 1);
    }
    if (s.params.blur != Blur::kNone) {
      timers.push_back(st.blur(default_pipeline()).run(st.gbuffer, s.params.blur, st.ao.get()));
    }
  }
  if (s.outputs.no_ao || s.outputs.with_ao || s.outputs.ao_only) {
    const BlendTarget target{st.blend_fb.get(),
                             {st.no_ao.get(), st.with_ao.get(), st.ao_only.get()}};
    timers.push_back(st.blend_pass(pipeline).run(st.gbuffer, want_ao ? st.ao.get() : 0, target));
  }
  glFinish();
  out.frame_ms = now_ms() - start_ms;
  out.pipeline = pipeline;
  check_gl("render");
  for (const PassTimer& t : timers) out.times.push_back(t.read());

  const int w = s.width, h = s.height;
  auto rgba = [&](const Texture& t) {
    return read_texture(t.get(), w, h, GL_RGBA, GL_UNSIGNED_BYTE, CV_8UC4);
  };
  if (s.outputs.no_ao) out.no_ao = rgba(st.no_ao);
  if (s.outputs.with_ao) out.with_ao = rgba(st.with_ao);
  if (s.outputs.ao_only) out.ao_only = rgba(st.ao_only);
  out.depth = read_texture(st.gbuffer.depth.get(), w, h, GL_RED, GL_FLOAT, CV_32F);
  out.geometry_pixels = cv::countNonZero(out.depth > 0);
  if (s.outputs.normal)
    out.normal = read_texture(st.gbuffer.normal.get(), w, h, GL_RGB, GL_FLOAT, CV_32FC3);
  if (s.outputs.pass_hashes) {
    const auto floats = [&](const Texture& t, GLenum format, int type) {
      return read_texture(t.get(), w, h, format, GL_FLOAT, type);
    };
    out.pass_hashes.emplace_back(
        "gbuffer", texels_hash({out.depth, floats(st.gbuffer.normal, GL_RGBA, CV_32FC4),
                                rgba(st.gbuffer.albedo)}));
    if (want_ao) {
      const bool blurred = s.params.blur != Blur::kNone;
      out.pass_hashes.emplace_back(
          "ao", texels_hash({floats(blurred ? st.unblurred_ao : st.ao, GL_RED, CV_32F)}));
      if (blurred)
        out.pass_hashes.emplace_back("blur", texels_hash({floats(st.ao, GL_RED, CV_32F)}));
    }
    if (s.outputs.no_ao || s.outputs.with_ao || s.outputs.ao_only)
      out.pass_hashes.emplace_back("blend", texels_hash({out.no_ao, out.with_ao, out.ao_only}));
  }
  if (s.outputs.ao_float) {
    out.ao = read_texture(st.ao.get(), w, h, GL_RED, GL_FLOAT, CV_32F);
    // The shaders guard every division; should one ever slip, fail loudly, never write it.
    if (!cv::checkRange(out.ao, true, nullptr, 0.0, 1.0 + 1e-6)) {
      throw std::runtime_error("AO pass produced a value outside [0, 1] or a NaN");
    }
  }
  return out;
}

}  // namespace aosuite::renderer
