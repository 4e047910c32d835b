// The AO at half the image's width and height (`half_res = 1`): the G-buffer's depth and
// normals downsampled as MSSAO's levels are (mssao_downsample.glsl), the technique's own pass
// run on them, and its AO brought back to the image's size by a depth- and normal-aware
// upsample (half_res_upsample.glsl). A quarter of the pixels pay for the taps; the error
// this costs against the reference is in docs/results.md.
#pragma once

#include "renderer/frame.hpp"
#include "renderer/passes/ao_pass.hpp"

namespace aosuite::renderer {

class HalfResPass {
 public:
  explicit HalfResPass(Pipeline pipeline);
  // Downsamples `full` into gbuffer(); the first timer of a half-resolution frame.
  PassTimer downsample(const GBuffer& full);
  // The half-size G-buffer (depth and normals only), its camera, and the AO target the
  // technique's pass writes to (no depth buffer: its sky pixels answer 1 themselves).
  const GBuffer& gbuffer() const { return half_; }
  Camera camera(const Camera& full) const;
  AoTarget target() const { return {ao_fb_.get(), ao_.get()}; }
  // The half-size AO upsampled into `out`, the image's AO target.
  PassTimer upsample(const GBuffer& full, const AoTarget& out);

 private:
  Pipeline pipeline_;
  Program downsample_, upsample_;
  GBuffer half_;
  Texture ao_;
  Framebuffer ao_fb_;
};

}  // namespace aosuite::renderer
