#include "renderer/params.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "common/overloaded.hpp"

namespace aosuite::renderer {
namespace {

// Which techniques read a row, from what their registry rows say (technique.cpp): a new
// technique reads the shared rows without an edit here.
bool tapped(const TechniqueInfo& t) { return t.sampling == Sampling::kTaps; }
bool sliced(const TechniqueInfo& t) { return t.sampling == Sampling::kSlices; }
bool screen_space(const TechniqueInfo& t) { return t.space == Space::kScreen; }
bool every(const TechniqueInfo&) { return true; }
// A row only one technique reads.
template <Technique id>
bool only(const TechniqueInfo& t) {
  return t.id == id;
}
constexpr double kBig = 1e30;

// The table. Ranges are what the passes handle without NaN or a runaway cost, and keep one
// pixel's shader loops under llvmpipe's cap of 65,535 iterations per invocation, past which it
// silently ends them (at most 12,352: 64 slices x 64 steps, bench/README.md); search ranges
// are where `aosuite tune` looks (ao/tune_space.hpp), wide around every technique's default.
const ParamSpec kParams[] = {
    {"samples",
     "taps per pixel",
     tapped,
     +[](AoParams& p) -> int& { return p.samples; },
     1,
     1024,
     false,
     "7",
     {1, 32, true}},
    {"radius",
     "world-space radius, scene units",
     screen_space,
     +[](AoParams& p) -> float& { return p.radius; },
     0,
     kBig,
     true,
     "0.37",
     {}},
    {"radius_scale",
     "multiplies the radius the kernel reaches; the reference keeps the radius (XeGTAO's radius "
     "multiplier, which gtao.glsl applies besides)",
     screen_space,
     +[](AoParams& p) -> float& { return p.radius_scale; },
     0,
     100,
     true,
     "1.3",
     {0.5, 2.5, true}},
    {"bias",
     "depth or angle bias (each shader's header says which)",
     tapped,
     +[](AoParams& p) -> float& { return p.bias; },
     -kBig,
     kBig,
     false,
     "0.0123",
     {0, 0.1, false}},
    {"intensity",
     "sigma: scales the occlusion (PMI: 1 - visibility, before the contrast)",
     every,
     +[](AoParams& p) -> float& { return p.intensity; },
     -kBig,
     kBig,
     false,
     "0.77",
     {0.25, 4, true}},
    {"contrast",
     "k (Alchemy, SAO), power (UE4) or final power (GTAO, bitmask, PMI)",
     every,
     +[](AoParams& p) -> float& { return p.contrast; },
     0,
     kBig,
     true,
     "1.3",
     {0.25, 4, true}},
    {"blur",
     "none|gaussian|bilateral, after the AO pass",
     every,
     +[](AoParams& p) -> Blur& { return p.blur; },
     0,
     0,
     false,
     "gaussian",
     {}},
    {"half_res",
     "1 = the AO pass at half the width and height, then upsampled depth- and normal-aware "
     "(a quarter of the taps); 0 = at the image's size",
     screen_space,
     +[](AoParams& p) -> int& { return p.half_res; },
     0,
     1,
     false,
     "1",
     {}},
    {"level_weights",
     "MSSAO's five level intensities, e.g. \"1,0.5,0.3,0.3,0.3\"",
     only<Technique::kMssao>,
     +[](AoParams& p) -> std::array<float, 5>& { return p.mssao.level_weights; },
     0,
     kBig,
     false,
     "1,0.25,0,0,0.5",
     {0, 2, false}},
    {"max_pixel_radius",
     "MSSAO's per-level kernel cap in pixels",
     only<Technique::kMssao>,
     +[](AoParams& p) -> float& { return p.mssao.max_pixel_radius; },
     1,
     1024,
     false,
     "9",
     {}},
    {"viewpoints",
     "PMI viewpoints: 12, 42, 162, 642 or 2562",
     only<Technique::kPmi>,
     +[](AoParams& p) -> int& { return p.pmi.viewpoints; },
     12,
     2562,
     false,
     "42",
     {}},
    {"pmi_resolution",
     "PMI item buffer width in pixels",
     only<Technique::kPmi>,
     +[](AoParams& p) -> int& { return p.pmi.resolution; },
     16,
     8192,
     false,
     "320",
     {}},
    {"importance_best",
     "PMI: the k best views share 99 % of p(V); 0 = projected area",
     only<Technique::kPmi>,
     +[](AoParams& p) -> int& { return p.pmi.importance_best; },
     0,
     2562,
     false,
     "3",
     {}},
    {"slices",
     "GTAO and bitmask slices per pixel",
     sliced,
     +[](AoParams& p) -> int& { return p.gtao.slices; },
     1,
     64,
     false,
     "2",
     {1, 8, true}},
    {"steps",
     "GTAO and bitmask steps per side of a slice",
     sliced,
     +[](AoParams& p) -> int& { return p.gtao.steps; },
     1,
     64,
     false,
     "5",
     {1, 8, true}},
    {"falloff_range",
     "GTAO: share of the radius over which occluders fade out",
     only<Technique::kGtao>,
     +[](AoParams& p) -> float& { return p.gtao.falloff_range; },
     0,
     1,
     true,
     "0.4",
     {0.05, 1, false}},
    {"thin_occluder",
     "GTAO: thin-occluder compensation (0 = off)",
     only<Technique::kGtao>,
     +[](AoParams& p) -> float& { return p.gtao.thin_occluder; },
     0,
     0.7,
     false,
     "0.3",
     {0, 0.7, false}},
    {"exact_plane",
     "GTAO: 1 = samples on the slice and arcs over an open plane's, so an open plane is exactly "
     "1 (0 = XeGTAO's)",
     only<Technique::kGtao>,
     +[](AoParams& p) -> int& { return p.gtao.exact_plane; },
     0,
     1,
     false,
     "1",
     {0, 1, false}},
    // Capped so the shader's squared lengths stay finite.
    {"thickness",
     "bitmask: assumed thickness of every occluder, a share of the radius (radius x "
     "radius_scale), so it means the same at every scene scale",
     only<Technique::kBitmask>,
     +[](AoParams& p) -> float& { return p.bitmask.thickness; },
     0,
     1e6,
     false,
     "1.2",
     {0.04, 8, true}},
};

[[noreturn]] void bad_value(std::string_view key, std::string_view value, const char* why) {
  throw std::invalid_argument("parameter " + std::string(key) + "=" + std::string(value) + ": " +
                              why);
}

template <typename T>
T parse_number(std::string_view key, std::string_view value) {
  T out{};
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), out);
  if (ec == std::errc::result_out_of_range) bad_value(key, value, "out of range");
  if (ec != std::errc() || end != value.data() + value.size())
    bad_value(key, value, "not a number");
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(out)) bad_value(key, value, "not finite");
  }
  return out;
}

void check_range(const ParamSpec& s, double v) {
  const bool low = s.min_exclusive ? !(v > s.min) : !(v >= s.min);
  if (low || !(v <= s.max) || !std::isfinite(v)) {
    const std::string range = s.max >= kBig
                                  ? fmt::format("{} {:g}", s.min_exclusive ? ">" : ">=", s.min)
                                  : fmt::format("{:g}..{:g}", s.min, s.max);
    throw std::invalid_argument(fmt::format("{} must be {} (got {:g})", s.key, range, v));
  }
}

// Throws std::invalid_argument when `p`'s value of `s` is out of its range.
void check_spec(const ParamSpec& s, const AoParams& p) {
  std::visit(Overloaded{[&](int v) { check_range(s, v); }, [&](float v) { check_range(s, v); },
                        [](const std::string&) {},
                        [&](const std::vector<float>& v) {
                          for (float w : v) check_range(s, w);
                        }},
             param_value(s, p));
}

}  // namespace

std::span<const ParamSpec> param_specs() { return kParams; }

const ParamSpec& param_spec(std::string_view key) {
  for (const ParamSpec& s : kParams) {
    if (s.key == key) return s;
  }
  throw std::invalid_argument(
      fmt::format("unknown parameter '{}' (known: {})", key, fmt::join(param_names(), ", ")));
}

bool applies(const ParamSpec& spec, Technique t) { return spec.reads(technique_info(t)); }

std::vector<std::string_view> param_names() {
  std::vector<std::string_view> out;
  for (const ParamSpec& s : kParams) out.push_back(s.key);
  return out;
}

void set_param(AoParams& p, std::string_view key, std::string_view value) {
  const ParamSpec& s = param_spec(key);
  std::visit(Overloaded{[&](int& (*f)(AoParams&)) { f(p) = parse_number<int>(key, value); },
                        [&](float& (*f)(AoParams&)) { f(p) = parse_number<float>(key, value); },
                        [&](Blur& (*f)(AoParams&)) { f(p) = parse_blur(value); },
                        [&](std::array<float, 5>& (*f)(AoParams&)) {
                          std::array<float, 5> w{};
                          std::size_t n = 0;
                          for (std::string_view rest = value;; ++n) {
                            const std::size_t comma = rest.find(',');
                            if (n < w.size())
                              w[n] = parse_number<float>(key, rest.substr(0, comma));
                            if (comma == std::string_view::npos) break;
                            rest.remove_prefix(comma + 1);
                          }
                          if (n + 1 != w.size())
                            bad_value(key, value, "needs five comma-separated values");
                          f(p) = w;
                        }},
             s.field);
  try {
    check_spec(s, p);
  } catch (const std::invalid_argument& e) {
    bad_value(key, value, e.what());
  }
}

void check_params(const AoParams& p) {
  for (const ParamSpec& s : kParams) check_spec(s, p);
  if (p.pmi.importance_best > p.pmi.viewpoints)
    throw std::invalid_argument("importance_best must be 0..viewpoints");
}

ParamValue param_value(const ParamSpec& s, const AoParams& p) {
  AoParams copy = p;
  return std::visit(Overloaded{[&](int& (*f)(AoParams&)) -> ParamValue { return f(copy); },
                               [&](float& (*f)(AoParams&)) -> ParamValue { return f(copy); },
                               [&](Blur& (*f)(AoParams&)) -> ParamValue {
                                 return std::string(blur_name(f(copy)));
                               },
                               [&](std::array<float, 5>& (*f)(AoParams&)) -> ParamValue {
                                 return std::vector<float>(f(copy).begin(), f(copy).end());
                               }},
                    s.field);
}

std::string param_text(const ParamSpec& s, const AoParams& p) {
  return std::visit(
      Overloaded{[](const std::string& v) { return v; },
                 [](const std::vector<float>& v) { return fmt::format("{}", fmt::join(v, ",")); },
                 [](auto v) { return fmt::format("{}", v); }},
      param_value(s, p));
}

}  // namespace aosuite::renderer
