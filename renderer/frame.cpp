#include "renderer/frame.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <thread>

#include "renderer/gl/gl_context.hpp"

namespace aosuite::renderer {
Camera make_camera(const View& v, int width, int height) {
  Camera c;
  c.width = width, c.height = height;
  glm::vec3 up = v.up;
  // Looking straight along `up` leaves lookAt undefined: pick another up vector.
  if (glm::length(glm::cross(glm::normalize(v.target - v.eye), up)) < 1e-6f) up = {0, 0, 1};
  c.view = glm::lookAt(v.eye, v.target, up);
  const float t = std::tan(glm::radians(v.fovy_degrees) * 0.5f);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  c.ndc_to_view = {t * aspect, t};
  c.proj_scale = static_cast<float>(height) / (2 * t);
  c.projection = glm::mat4(0);
  c.projection[0][0] = 1 / (t * aspect);
  c.projection[1][1] = 1 / t;
  c.projection[2][3] = -1;      // w = -z_view
  c.projection[3][2] = v.near;  // z_clip = near  ->  depth = near / distance
  return c;
}

GBuffer make_gbuffer(int width, int height) {
  GBuffer g;
  g.width = width, g.height = height;
  g.depth = make_texture(GL_R32F, width, height);
  g.normal = make_texture(GL_RGBA16F, width, height);
  g.albedo = make_texture(GL_RGBA8, width, height);
  g.zbuffer = make_texture(GL_DEPTH_COMPONENT32F, width, height);
  g.fb = make_framebuffer({g.depth.get(), g.normal.get(), g.albedo.get()}, g.zbuffer.get());
  return g;
}

void set_camera_uniforms(GLuint program, const Camera& camera) {
  glProgramUniform2f(program, glGetUniformLocation(program, "u_ndc_to_view"), camera.ndc_to_view.x,
                     camera.ndc_to_view.y);
}

void set_view_projection(GLuint program, const Camera& camera) {
  glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "u_view"), 1, GL_FALSE,
                            glm::value_ptr(camera.view));
  glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "u_projection"), 1, GL_FALSE,
                            glm::value_ptr(camera.projection));
}

namespace {

// The vertex shader makes the triangle from gl_VertexID; the context keeps an empty vertex
// array bound for it (GlContext).
void bind_fullscreen(GLuint fb, int width, int height) {
  glBindFramebuffer(GL_FRAMEBUFFER, fb);
  glViewport(0, 0, width, height);
}

}  // namespace

void draw_fullscreen(GLuint fb, int width, int height) {
  bind_fullscreen(fb, width, height);
  glDisable(GL_DEPTH_TEST);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void draw_geometry_pixels(GLuint fb, int width, int height) {
  const float sky[4] = {1, 0, 0, 1};  // AO 1 (and depth 0 where a target keeps depth)
  glClearNamedFramebufferfv(fb, GL_COLOR, 0, sky);
  bind_fullscreen(fb, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_LESS);  // the triangle is at depth 0: passes only where geometry stored > 0
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_DEPTH_TEST);
}

void bind_textures(GLuint program, std::initializer_list<std::pair<const char*, GLuint>> textures) {
  glUseProgram(program);
  GLint unit = 0;
  for (const auto& [name, tex] : textures) {
    glBindTextureUnit(static_cast<GLuint>(unit), tex);
    glProgramUniform1i(program, glGetUniformLocation(program, name), unit);
    ++unit;
  }
}

int light_pass_rows() {
  if (const char* env = std::getenv("AOSUITE_PIXEL_ROWS"); env && *env) {
    return static_cast<int>(std::clamp(std::strtol(env, nullptr, 10), 1L, 2L));
  }
  return 2;
}

Program make_pixel_program(const char* file, int rows) {
  return make_program({file}, "#define PIXEL_GROUP " + std::to_string(kPixelGroup) +
                                  "\n#define PIXEL_ROWS " + std::to_string(rows) + "\n");
}

namespace {

// Whether the current context renders on this CPU (llvmpipe, softpipe): a software renderer.
bool device_is_cpu() {
  const auto* device = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return device && software_renderer(device);
}

}  // namespace

int dispatch_shares() {
  if (!device_is_cpu()) return 1;
  long threads = std::thread::hardware_concurrency();
  if (const char* env = std::getenv("LP_NUM_THREADS"); env && *env) {
    threads = std::strtol(env, nullptr, 10);  // as Mesa reads it
  }
  return static_cast<int>(std::clamp(threads, 1L, 256L));
}

void dispatch_rows(GLuint program, GLuint groups_x, GLuint groups_y) {
  const auto shares = static_cast<GLuint>(dispatch_shares());
  glProgramUniform1i(program, glGetUniformLocation(program, "u_dispatch_shares"),
                     static_cast<GLint>(shares));
  glUseProgram(program);
  glDispatchCompute(groups_x, (groups_y + shares - 1) / shares * shares, 1);
}

void dispatch_pixels(GLuint program, std::initializer_list<std::pair<GLuint, GLenum>> images,
                     int width, int height, int rows) {
  GLuint unit = 0;
  for (const auto& [tex, format] : images) {
    glBindImageTexture(unit++, tex, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
  }
  glProgramUniform2i(program, glGetUniformLocation(program, "u_pixels"), width, height);
  const auto groups = [](int n, int span) { return static_cast<GLuint>((n + span - 1) / span); };
  dispatch_rows(program, groups(width, kPixelGroup), groups(height, kPixelGroup * rows));
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                  GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace

PassTimer::PassTimer(std::string name) : name_(std::move(name)) {
  if (device_is_cpu()) {
    glFinish();
    start_ = std::chrono::steady_clock::now();
    return;
  }
  GLuint id = 0;
  glCreateQueries(GL_TIME_ELAPSED, 1, &id);
  query_ = Query(id);
  // Submit the work so far (no wait): a rasteriser that bins a query's begin into whatever
  // batch is open would stamp it while the previous pass still runs and charge that pass's
  // tail to this one.
  glFlush();
  glBeginQuery(GL_TIME_ELAPSED, id);
}

void PassTimer::stop() {
  if (query_.get() == 0) {
    glFinish();
    wall_ms_ = ms_since(start_);
    return;
  }
  glEndQuery(GL_TIME_ELAPSED);
}

PassTime PassTimer::read() const {
  if (query_.get() == 0) return {name_, wall_ms_};
  GLuint64 ns = 0;
  glGetQueryObjectui64v(query_.get(), GL_QUERY_RESULT, &ns);
  return {name_, static_cast<double>(ns) * 1e-6};
}

}  // namespace aosuite::renderer
