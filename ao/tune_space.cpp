#include "ao/tune_space.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "common/overloaded.hpp"

namespace aosuite::ao {
namespace {

namespace rd = aosuite::renderer;

// Three significant digits: a preset reads back as the value that was measured (parsed as
// set_param parses it, with from_chars: no locale).
float round3(double v) {
  const std::string text = fmt::format("{:.3g}", v);
  float out = 0;
  std::from_chars(text.data(), text.data() + text.size(), out);
  return out;
}

double to_value(const rd::SearchRange& r, double u) {
  u = std::clamp(u, 0.0, 1.0);
  return r.log ? std::exp(std::log(r.lo) + u * (std::log(r.hi) - std::log(r.lo)))
               : r.lo + u * (r.hi - r.lo);
}

double to_unit(const rd::SearchRange& r, double v) {
  v = std::clamp(v, r.lo, r.hi);
  return r.log ? (std::log(v) - std::log(r.lo)) / (std::log(r.hi) - std::log(r.lo))
               : (v - r.lo) / (r.hi - r.lo);
}

}  // namespace

TuneSpace::TuneSpace(rd::Technique technique) : technique_(technique) {
  for (const rd::ParamSpec& spec : rd::param_specs()) {
    if (!spec.search.searched() || !rd::applies(spec, technique)) continue;
    std::visit(Overloaded{[&](int& (*)(rd::AoParams&)) {
                            dims_.push_back({&spec, 0, true});
                          },
                          [&](float& (*)(rd::AoParams&)) {
                            dims_.push_back({&spec, 0, false});
                          },
                          [&](std::array<float, 5>& (*)(rd::AoParams&)) {
                            for (int i = 0; i < 5; ++i) dims_.push_back({&spec, i, false});
                          },
                          [](rd::Blur& (*)(rd::AoParams&)) {}},
               spec.field);
  }
  if (dims_.empty()) {  // none registered now; a new technique whose rows give no search range
    throw std::invalid_argument(
        fmt::format("{} has no parameter the tuner searches", rd::technique_name(technique)));
  }
}

rd::AoParams TuneSpace::params(const std::vector<double>& point, rd::AoParams p) const {
  for (std::size_t i = 0; i < dims_.size(); ++i) {
    const Dimension& d = dims_[i];
    const double v = to_value(d.spec->search, point[i]);
    std::visit(
        Overloaded{[&](int& (*f)(rd::AoParams&)) { f(p) = static_cast<int>(std::lround(v)); },
                   [&](float& (*f)(rd::AoParams&)) { f(p) = round3(v); },
                   [&](std::array<float, 5>& (*f)(rd::AoParams&)) {
                     f(p)[static_cast<std::size_t>(d.element)] = round3(v);
                   },
                   [](rd::Blur& (*)(rd::AoParams&)) {}},
        d.spec->field);
  }
  return p;
}

std::vector<double> TuneSpace::point(const rd::AoParams& p) const {
  std::vector<double> out;
  for (const Dimension& d : dims_) {
    const rd::ParamValue v = rd::param_value(*d.spec, p);
    const double x = std::visit(
        Overloaded{[](int i) { return double(i); }, [](float f) { return double(f); },
                   [&](const std::vector<float>& w) { return double(w[std::size_t(d.element)]); },
                   [](const std::string&) { return 0.0; }},
        v);
    out.push_back(to_unit(d.spec->search, x));
  }
  return out;
}

std::vector<std::pair<std::string, std::string>> TuneSpace::entries(const rd::AoParams& p) const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const Dimension& d : dims_) {
    if (d.element == 0) out.emplace_back(std::string(d.spec->key), rd::param_text(*d.spec, p));
  }
  return out;
}

rd::AoParams TuneSpace::between(const rd::AoParams& from, const rd::AoParams& to, double t) const {
  if (t <= 0) return from;
  if (t >= 1) return to;
  const std::vector<double> a = point(from), b = point(to);
  std::vector<double> mid(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) mid[i] = a[i] + t * (b[i] - a[i]);
  return params(mid, from);
}

std::string TuneSpace::key(const rd::AoParams& p) const {
  std::string out;
  for (const auto& [k, v] : entries(p)) out += (out.empty() ? "" : " ") + k + "=" + v;
  return out;
}

}  // namespace aosuite::ao
