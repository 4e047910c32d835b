#include "compare/metric.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace aosuite::metric {

double Measurement::value(std::string_view key) const {
  for (const Value& v : values)
    if (v.key == key) return v.value;
  throw std::out_of_range(fmt::format("{} has no value '{}'", metric, key));
}

nlohmann::ordered_json Measurement::json() const {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  // JSON has no infinity: PSNR of identical images is written as null.
  for (const Value& v : values)
    j[v.key] = std::isfinite(v.value) ? nlohmann::ordered_json(v.value) : nullptr;
  for (const Value& v : facts) j[v.key] = v.value;
  if (nonfinite) j["nonfinite"] = nonfinite;
  return j;
}

const Metric& find(std::string_view name) {
  for (const Metric* m : all())
    if (m->name == name) return *m;
  throw std::invalid_argument(fmt::format("unknown metric '{}' (metrics: {})", name, names()));
}

std::string names() {
  std::string out;
  for (const Metric* m : all()) out += (out.empty() ? "" : ", ") + std::string(m->name);
  return out;
}

namespace {

// Pixels where either image has a NaN or Inf sample; those samples become 0 when `clean`.
std::uint64_t count_nonfinite(FloatImage& a, FloatImage& b, bool clean) {
  const std::size_t n = std::size_t(a.channels);
  std::uint64_t count = 0;
  for (std::size_t i = 0; i < a.data.size(); i += n) {
    bool bad = false;
    for (std::size_t c = i; c < i + n; ++c) {
      for (float* v : {&a.data[c], &b.data[c]}) {
        if (std::isfinite(*v)) continue;
        bad = true;
        if (clean) *v = 0.0f;
      }
    }
    count += bad;
  }
  return count;
}

}  // namespace

Measurement measure(const Metric& metric, const Picture& reference, const Picture& test,
                    const Request& request) {
  const ImageSize sa = reference.size(), sb = test.size();
  if (sa.width != sb.width || sa.height != sb.height) {
    throw std::invalid_argument(fmt::format(
        "{}: {}x{}, but {} is {}x{}: {} compares images of "
        "one size",
        test.name, sb.width, sb.height, reference.name, sa.width, sa.height, metric.name));
  }
  if (!same_kind(reference, test)) {
    throw std::invalid_argument(fmt::format("{}: {}, but {} is {}: {} compares images of one kind",
                                            test.name, test.kind(), reference.name,
                                            reference.kind(), metric.name));
  }
  if (request.counted &&
      request.counted->size() != std::size_t(sa.width) * std::size_t(sa.height)) {
    throw std::invalid_argument(
        fmt::format("{}: the pixel mask is not {}x{}", metric.name, sa.width, sa.height));
  }
  if (!reference.is_float) return metric.measure(reference, test, request);
  Picture a = reference, b = test;  // FloatImage copies: the originals stay as read
  if (a.floats.channels != b.floats.channels) widen_grey(a.floats), widen_grey(b.floats);
  const std::uint64_t nonfinite = count_nonfinite(a.floats, b.floats, !metric.raw_floats);
  Measurement m = metric.measure(a, b, request);
  m.nonfinite = nonfinite;
  return m;
}

std::string gate_keys(const Metric& m) {
  std::string out = "max, min";
  for (std::string_view s : m.stats) out += fmt::format(", max_{0}, min_{0}", s);
  return out + ", allow_nonfinite";
}

void add_gate(Gates& gates, std::string_view key, double value) {
  const Metric& m = *gates.metric;
  if (key == "allow_nonfinite") {
    gates.allow_nonfinite = value != 0;
    return;
  }
  if (!std::isfinite(value)) {
    throw std::invalid_argument(
        fmt::format("{}.{}: the limit must be a finite number", m.name, key));
  }
  Limit l;
  l.limit = value;
  if (key == "max" || key == "min") {
    l.is_max = key == "max", l.stat = std::string(m.primary);
  } else if (key.starts_with("max_") || key.starts_with("min_")) {
    l.is_max = key.starts_with("max_"), l.stat = std::string(key.substr(4));
  }
  if (std::find(m.stats.begin(), m.stats.end(), l.stat) == m.stats.end()) {
    throw std::invalid_argument(
        fmt::format("{} has no gate '{}' (gates: {})", m.name, key, gate_keys(m)));
  }
  gates.limits.push_back(l);
}

Gates& gates_for(std::vector<Gates>& list, const Metric& m) {
  for (Gates& g : list)
    if (g.metric == &m) return g;
  return list.emplace_back(Gates{&m, {}, false});
}

void add_gate_spec(std::vector<Gates>& list, std::string_view spec) {
  const std::size_t dot = spec.find('.'), eq = spec.find('=');
  if (dot == std::string_view::npos || eq == std::string_view::npos || eq < dot) {
    throw std::invalid_argument(fmt::format(
        "--gate '{}' is not METRIC.KEY=VALUE (e.g. flip.max_mean=0.02, ssim.min=0.98)", spec));
  }
  const Metric& m = find(spec.substr(0, dot));
  const std::string text(spec.substr(eq + 1));
  double value = text == "true" ? 1 : 0;
  if (text != "true" && text != "false") {
    char* end = nullptr;
    errno = 0;
    value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(value)) {
      throw std::invalid_argument(
          fmt::format("--gate '{}': '{}' is not a finite number", spec, text));
    }
  }
  add_gate(gates_for(list, m), spec.substr(dot + 1, eq - dot - 1), value);
}

std::string Outcome::text() const {
  const std::string where = region.empty() ? "" : region + ": ";
  if (stat == "nonfinite")
    return fmt::format("{}{}: {} pixels are NaN or Inf", where, metric, value);
  const char* op = pass ? (is_max ? "<=" : ">=") : (is_max ? ">" : "<");
  return fmt::format("{}{} {} {:.6g} {} {:.6g}", where, metric, stat, value, op, limit);
}

std::vector<Outcome> judge(const Gates& gates, const Measurement& m) {
  std::vector<Outcome> out;
  // Only a gated metric judges: measured alone, NaN and Inf are counted, not failed.
  if (m.nonfinite && !gates.allow_nonfinite && !gates.limits.empty()) {
    out.push_back(
        {m.metric, "nonfinite", "", double(m.nonfinite), 0, true, -double(m.nonfinite), false});
  }
  for (const Limit& l : gates.limits) {
    Outcome o{m.metric, l.stat, "", m.value(l.stat), l.limit, l.is_max, 0, false};
    o.margin = l.is_max ? l.limit - o.value : o.value - l.limit;
    // +inf PSNR (identical images) passes any min and fails any max, with an infinite margin.
    o.pass = o.margin >= 0;
    out.push_back(o);
  }
  return out;
}

namespace {

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

// null is the infinity a finite-only format could not hold: +inf for a value, as PSNR's.
double number_from(const nlohmann::json& j, double infinity = HUGE_VAL) {
  return j.is_null() ? infinity : j.get<double>();
}

}  // namespace

nlohmann::json to_json(const Outcome& o) {
  return {{"metric", o.metric},
          {"stat", o.stat},
          {"region", o.region},
          {"value", number_or_null(o.value)},
          {"limit", o.limit},
          {"bound", o.is_max ? "max" : "min"},
          {"margin", number_or_null(o.margin)},
          {"pass", o.pass}};
}

Outcome outcome_from_json(const nlohmann::json& j) {
  Outcome o;
  o.metric = j.at("metric"), o.stat = j.at("stat"), o.region = j.value("region", "");
  o.value = number_from(j.at("value")), o.limit = j.at("limit");
  o.is_max = j.at("bound") == "max";
  o.margin = number_from(j.at("margin"), o.is_max ? -HUGE_VAL : HUGE_VAL);
  o.pass = j.at("pass");
  return o;
}

Measurement measurement_from_json(const Metric& m, const nlohmann::json& j) {
  Measurement out;
  out.metric = std::string(m.name);
  for (const auto& [key, value] : j.items()) {
    if (key == "nonfinite") {
      out.nonfinite = value;
    } else if (std::find(m.stats.begin(), m.stats.end(), key) != m.stats.end()) {
      out.values.push_back({key, number_from(value)});
    } else {
      out.facts.push_back({key, value.get<double>()});
    }
  }
  return out;
}

nlohmann::json to_json(const Gates& g) {
  nlohmann::json j = nlohmann::json::object();
  for (const Limit& l : g.limits) j[(l.is_max ? "max_" : "min_") + l.stat] = l.limit;
  if (g.allow_nonfinite) j["allow_nonfinite"] = true;
  return j;
}

Gates gates_from_json(const Metric& m, const nlohmann::json& j) {
  Gates g{&m, {}, false};
  for (const auto& [key, value] : j.items())
    add_gate(g, key, value.is_boolean() ? double(value.get<bool>()) : value.get<double>());
  return g;
}

}  // namespace aosuite::metric
