// What every pass shares: the camera, the G-buffer, and per-pass timing.
#pragma once

#include <chrono>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "renderer/gl/gl_objects.hpp"
#include "renderer/scene/scene.hpp"

namespace aosuite::renderer {

struct Camera {
  int width = 0, height = 0;
  glm::mat4 view{1}, projection{1};
  glm::vec2 ndc_to_view{1};  // (tan(fovy/2) * aspect, tan(fovy/2))
  float proj_scale = 1;      // pixels covered by 1 unit at distance 1: H / (2 tan(fovy/2))
};
// Reversed-Z infinite perspective: depth = near / z, so DEPTH32F keeps precision from the
// near plane to any distance (near/far ratios of 1e-4 to 1e6 in the stress tests).
Camera make_camera(const View& view, int width, int height);

// The view-space position of image pixel (x, row) (top row first, as Images stores them) at
// linear depth z: common.glsl's view_position for the same pixel centre, for CPU-side passes.
inline glm::vec3 view_position(const Camera& c, int x, int row, float z) {
  const glm::vec2 centre{static_cast<float>(x) + 0.5f, static_cast<float>(c.height - row) - 0.5f};
  const glm::vec2 ndc = centre / glm::vec2(c.width, c.height) * 2.0f - 1.0f;
  return {ndc * c.ndc_to_view * z, -z};
}

struct GBuffer {
  int width = 0, height = 0;
  Texture depth;    // R32F linear view depth; 0 = background
  Texture normal;   // RGBA16F view-space normal
  Texture albedo;   // RGBA8
  Texture zbuffer;  // DEPTH32F, reversed
  Framebuffer fb;
};
GBuffer make_gbuffer(int width, int height);

// Sets u_ndc_to_view on `program` (common.glsl's; skipped if the program lacks it). The AO
// passes' u_proj_scale is in their uniform block (ao_uniforms.hpp).
void set_camera_uniforms(GLuint program, const Camera& camera);
// u_view and u_projection, for the passes that rasterise the scene's triangles.
void set_view_projection(GLuint program, const Camera& camera);

// Binds `textures` to units 0..n-1 and the sampler uniforms named alongside them, and makes
// `program` current.
void bind_textures(GLuint program, std::initializer_list<std::pair<const char*, GLuint>> textures);

// Draws the full-screen triangle into `fb` at the given size.
void draw_fullscreen(GLuint fb, int width, int height);

// The same, but only where there is geometry: `fb` must carry the G-buffer's depth buffer,
// whose background is 0 (reversed Z), so the depth test rejects sky pixels before they are
// shaded. Colour attachment 0 is first cleared to 1, the AO of the sky.
void draw_geometry_pixels(GLuint fb, int width, int height);

// The compute passes' workgroups: kPixelGroup x kPixelGroup invocations.
inline constexpr int kPixelGroup = 8;

// How many pixels each invocation shades (pixel_main.glsl's PIXEL_ROWS, one above another) in
// the pixel programs of a few instructions a pixel, the blend and the depth G-buffer's normals:
// 2, which costs less on both kinds of device measured (bench/README.md, "Two pixels an
// invocation"). On llvmpipe, which calls a coroutine per 8-wide vector of invocations where its
// rasteriser calls a function per 4x4 block of fragments, the 1080p blend took 33 ms against
// 39 ms at one pixel and 32 ms drawn; on an H200 0.024 against 0.028 ms. The AO estimators keep
// 1: at 2, UE4's and GTAO's took longer on llvmpipe. $AOSUITE_PIXEL_ROWS (1 or 2) overrides it,
// for tests and measurements.
int light_pass_rows();

// Links compute shader `file` with PIXEL_GROUP defined as kPixelGroup (its local size) and
// PIXEL_ROWS as `rows`: a pixel program, which dispatch_pixels runs with the same rows.
Program make_pixel_program(const char* file, int rows = 1);

// How many contiguous runs the device splits a dispatch's workgroups into, one per thread:
// Mesa's software rasterisers give each compute thread one (LP_NUM_THREADS of them, by default
// one per CPU); a GPU hands workgroups to its units as they free up, so 1 there. A wrong count
// costs only balance between threads: dispatch_rows's map is one to one for any count.
int dispatch_shares();

// Makes `program` current and dispatches groups_x x groups_y workgroups whose rows its shader
// maps through dispatch_order.glsl's image_workgroup(), so that each of the device's shares of
// the dispatch covers the whole image: the rows rounded up to a multiple of dispatch_shares().
void dispatch_rows(GLuint program, GLuint groups_x, GLuint groups_y);

// Binds `images` (texture, format) to image units 0..n-1 for writing, sets the pixel program's
// u_pixels to width x height and dispatches (dispatch_rows) its workgroups over them, `rows`
// pixels an invocation (make_pixel_program's); then orders those writes before what reads them
// next (texel fetches, framebuffer use, read-back), as a draw's would be. A shader whose pixels
// cost the same keeps the workgroups' own order (the blend: interleaved, it measured slower on
// llvmpipe) and skips the spare rows as it skips a partial workgroup's.
void dispatch_pixels(GLuint program, std::initializer_list<std::pair<GLuint, GLenum>> images,
                     int width, int height, int rows = 1);

struct PassTime {
  std::string pass;
  double gpu_ms = 0;  // the device's time: GL_TIME_ELAPSED on a GPU, wall time on a CPU (PassTimer)
};

// Times one pass. On a GPU without stalling it: construction begins a GL_TIME_ELAPSED query
// and stop() ends it; read() waits for the result, so call it once the frame's work is done
// (a glFinish or the read-back has waited already). Waiting after every pass would drain the
// pipeline between passes, which on a GPU costs more than the short passes themselves.
// On a software renderer, whose device is this CPU, by the wall clock between a glFinish at
// construction and one at stop(): llvmpipe's GL_TIME_ELAPSED charges a dispatch's work, and a
// draw's in a context that also dispatches, to no pass or another (SAO's dispatched AO pass read
// 0.25 ms where it took 59 ms, the G-buffer before it 0.08 ms where it took 19; bench/README.md).
class PassTimer {
 public:
  explicit PassTimer(std::string name);
  void stop();
  PassTime read() const;

 private:
  std::string name_;
  Query query_;  // none on a CPU
  std::chrono::steady_clock::time_point start_;
  double wall_ms_ = 0;
};

}  // namespace aosuite::renderer
