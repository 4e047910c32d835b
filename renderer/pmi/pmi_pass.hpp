// PMI's AO pass: the scene drawn with each vertex's PMI visibility (ground: 1), interpolated
// across its triangles and mapped by the intensity and contrast parameters (pmi_ao.frag), into
// the AO target wherever the G-buffer saw that same surface.
#pragma once

#include "renderer/frame.hpp"
#include "renderer/pmi/pmi_channel.hpp"

namespace aosuite::renderer {

class PmiPass {
 public:
  PmiPass();
  // `out_fb` must carry the G-buffer's depth (as the Renderer's AO target does).
  PassTimer run(const Scene& scene, const PmiMaps& maps, const Camera& camera,
                const AoParams& params, GLuint out_fb) const;

 private:
  Program program_;
};

}  // namespace aosuite::renderer
