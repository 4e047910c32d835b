// The AO techniques of the study: one registry (technique.cpp's kTechniques) that parsing,
// help text, the pass factory, the harness and the tests all iterate, and the parameters they
// take (params.hpp's table). Adding a technique: docs/adding-a-technique.md.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace aosuite::renderer {

// kPmi: viewpoint-based AO (González, Sbert & Feixas 2008), per polygon in object space
// (renderer/pmi/pmi_channel.hpp), not a screen-space estimator.
enum class Technique { kAlchemy, kSao, kMssao, kUe4, kPmi, kGtao, kBitmask };

enum class Blur { kNone, kGaussian, kBilateral };

// How the screen-space passes run: draws whose pixels the rasteriser shades (fragment), or
// compute dispatches over the image (compute). Both run the same estimator code (a technique's
// .glsl, included by its .frag and .comp) and write the same AO texture, which the blur and
// blend read. Compute exists for GPUs whose fragment shading runs on few units (Hopper:
// bench/README.md); the G-buffer and PMI's maps are rasterised in either.
enum class Pipeline { kFragment, kCompute };
Pipeline parse_pipeline(std::string_view name);  // fragment|compute
std::string_view pipeline_name(Pipeline p);

// What the G-buffer pass rasterises. Full: depth, normals and albedo, a fragment shader per
// pixel. Depth: the depth buffer alone, then one dispatch reconstructs linear depth and normals
// from it (XeGTAO's input); it has no colour, so the lit images are untextured (albedo 0.8).
// On an H200 the depth-only G-buffer costs a fourth of the full one (bench/README.md).
enum class GBufferKind { kFull, kDepth };
GBufferKind parse_gbuffer(std::string_view name);  // full|depth
std::string_view gbuffer_name(GBufferKind g);
Blur parse_blur(std::string_view name);  // none|gaussian|bilateral
std::string_view blur_name(Blur b);

// MSSAO (Hoang & Low 2012).
struct MssaoParams {
  // Intensity of each of the five levels (full, 1/2, 1/4, 1/8, 1/16), times `intensity`;
  // 0 skips a level.
  std::array<float, 5> level_weights{1.0f, 0.5f, 0.3f, 0.3f, 0.3f};
  // r_max, the most pixels a level's kernel reaches at that level's resolution (Hoang & Low's
  // cap, so each level costs the same). It is a pixel count, so at 3840x2160 the five levels
  // reach half as far in the scene as at 1920x1080; 10 there matches 5 here.
  float max_pixel_radius = 5;
};

// PMI: viewpoints on the subdivided icosahedron (12, 42, 162, 642 or 2562), the item buffer's
// width in pixels (its height is 3/4 of it, as the paper's 640x480..2560x1920), and p(V):
// 0 = projected area (the paper), k > 0 = the k best views (lowest VMI) share 99 % of the
// importance and the rest share 1 % (the paper's Figure 7).
struct PmiParams {
  int viewpoints = 162;
  int resolution = 1280;
  int importance_best = 0;
};

// GTAO (Jimenez et al. 2016) with XeGTAO's "High" preset: 3 slices x 3 steps per side.
struct GtaoParams {
  int slices = 3;
  int steps = 3;                 // per side of each slice
  float falloff_range = 0.615f;  // share of the radius over which occluders fade out
  float thin_occluder = 0;       // XeGTAO's ThinOccluderCompensation
  // 1: each horizon sample on the slice itself (its depth interpolated in 1/z, exact on a plane,
  // from one gather of the four texels around it) and the arcs divided by those of an open
  // plane, so an open plane is exactly 1; 0: XeGTAO's, whose samples snap to texel centres.
  int exact_plane = 0;
};

// Visibility bitmask (Therrien et al. 2023): GTAO's slices and steps (GtaoParams), and the
// thickness every sample is assumed to have behind its visible front, as a share of the
// radius (radius x radius_scale): a length in scene units would mean a thin shell on a
// building and a thick slab on a statuette (issue 45). 0.5 is 0.25 units at the default
// radius 0.5, the absolute default it replaced.
struct BitmaskParams {
  float thickness = 0.5f;
};

struct AoParams {
  int samples = 16;
  float radius = 1;  // scene units
  // The kernel reaches radius * radius_scale while the study (and its reference) keeps
  // `radius`: XeGTAO's tuned radius multiplier, for every technique (what `aosuite tune` finds).
  float radius_scale = 1;
  float bias = 0;       // technique-specific units, see each shader's header
  float intensity = 1;  // sigma
  float contrast = 1;   // k (Alchemy, SAO), power (UE4), final power (GTAO)
  Blur blur = Blur::kBilateral;
  // 1: the screen-space AO pass at half the width and height, brought back up depth-aware
  // (passes/half_res_pass.hpp); 0: at the image's size.
  int half_res = 0;
  MssaoParams mssao;
  PmiParams pmi;
  GtaoParams gtao;
  BitmaskParams bitmask;
};

class AoPass;

enum class Space { kScreen, kObject };
// How a screen-space estimator samples: s taps within the radius (with a bias), or GTAO's
// slices and steps. Says which of the parameter table's shared rows it reads (params.cpp).
enum class Sampling { kTaps, kSlices, kNone };

struct TechniqueInfo {
  Technique id;
  std::string_view name;     // as suites and --technique spell it
  std::string_view summary;  // one line: what it is, after whom
  Space space;               // screen space: an AoPass over the G-buffer
  Sampling sampling;
  AoParams (*defaults)();  // the published parameters
  // Depth fetches per pixel of the AO pass at these parameters: the cost `aosuite tune`'s
  // budget holds (GTAO's High preset: 3 slices x 3 steps x 2 sides = 18). 0 for object space.
  int (*depth_taps)(const AoParams&);
  // The screen-space pass of each pipeline, the same estimator drawn or dispatched; null for
  // object-space techniques, which the Renderer runs itself (rasterised in both pipelines).
  std::unique_ptr<AoPass> (*make_fragment_pass)();
  std::unique_ptr<AoPass> (*make_compute_pass)();
};

// Every technique, in the order help text and tests list them.
std::span<const TechniqueInfo> techniques();
const TechniqueInfo& technique_info(Technique t);
// Throws std::invalid_argument naming the known techniques.
Technique parse_technique(std::string_view name);
std::string_view technique_name(Technique t);
// "alchemy|sao|..." with `separator` between the names.
std::string technique_names(std::string_view separator);
inline AoParams default_params(Technique t) { return technique_info(t).defaults(); }
// Object space (PMI): the Renderer draws the technique's cached per-polygon maps itself
// instead of running an AoPass over the G-buffer.
inline bool object_space(Technique t) { return technique_info(t).space == Space::kObject; }
// The registered screen-space techniques' names, in registry order: what a suite renders when
// it names no techniques.
std::vector<std::string> screen_space_technique_names();

}  // namespace aosuite::renderer
