#include "compare/verdict.hpp"

#include <fmt/format.h>

#include <string>

namespace aosuite::verdict {

std::string Verdict::message() const {
  std::string out;
  for (const std::string& f : failed) out += (out.empty() ? "" : "; ") + f;
  return out;
}

namespace {

// The two-sided budgets' lower ends, and the differing pixels' upper end.
void budgets(const ResembleFigures& r, const ResembleAllowance& a,
             std::vector<std::string>& failed) {
  if (r.max_channel_delta >= 0 && r.max_channel_delta < a.min_channel_delta) {
    failed.push_back(fmt::format(
        "max channel delta {} (budget {}..{}: the difference it allows for is gone; tighten it)",
        r.max_channel_delta, a.min_channel_delta, a.max_channel_delta));
  }
  if (r.differing_pixels < 0) return;
  const bool over = a.max_differing_pixels >= 0 && r.differing_pixels > a.max_differing_pixels;
  if (over || r.differing_pixels < a.min_differing_pixels) {
    failed.push_back(fmt::format(
        "{} differing pixels (budget {}..{}{})", r.differing_pixels, a.min_differing_pixels,
        a.max_differing_pixels < 0 ? std::string("any") : std::to_string(a.max_differing_pixels),
        over ? "" : ": the difference it allows for is gone; tighten it"));
  }
}

}  // namespace

Verdict decide(const ResembleFigures* resemble, const ResembleAllowance& allowed,
               std::span<const metric::Outcome> gates) {
  Verdict v;
  if (resemble) {
    if (!resemble->same_size) {
      v.failed.push_back("the images differ in size");
    } else {
      // Each limit that failed, and only those.
      if (resemble->mismatch_percent > allowed.max_mismatch_percent) {
        v.failed.push_back(fmt::format("mismatch {}% (allowed {}%)", resemble->mismatch_text,
                                       allowed.max_mismatch_percent));
      }
      if (resemble->max_channel_delta > allowed.max_channel_delta) {
        v.failed.push_back(fmt::format("max channel delta {} (allowed {})",
                                       resemble->max_channel_delta, allowed.max_channel_delta));
      }
      if (resemble->mean_shift > allowed.max_mean_shift) {
        v.failed.push_back(fmt::format("mean shift {:.3g} levels (allowed {:g})",
                                       resemble->mean_shift, allowed.max_mean_shift));
      }
      if (resemble->mean_delta > allowed.max_mean_delta) {
        v.failed.push_back(fmt::format("mean delta {:.3g} levels (allowed {:g})",
                                       resemble->mean_delta, allowed.max_mean_delta));
      }
      budgets(*resemble, allowed, v.failed);
    }
  }
  for (const metric::Outcome& o : gates)
    if (!o.pass) v.failed.push_back(o.text());
  v.pass = v.failed.empty();
  return v;
}

std::vector<std::string> stale_budgets(const ResembleFigures* resemble,
                                       const ResembleAllowance& allowed,
                                       std::span<const metric::Outcome> gates) {
  std::vector<std::string> out;
  const auto unused = [](double used, double limit) { return limit > 0 && used * 10 < limit; };
  if (resemble && resemble->same_size) {
    if (unused(resemble->mismatch_percent, allowed.max_mismatch_percent)) {
      out.push_back(fmt::format("max_mismatch_percent {} (used {})", allowed.max_mismatch_percent,
                                resemble->mismatch_text));
    }
    if (resemble->differing_pixels >= 0 &&
        unused(double(resemble->differing_pixels), double(allowed.max_differing_pixels))) {
      out.push_back(fmt::format("differing_pixels max {} (used {})", allowed.max_differing_pixels,
                                resemble->differing_pixels));
    }
  }
  for (const metric::Outcome& o : gates) {
    if (o.is_max && o.pass && unused(o.value, o.limit)) {
      out.push_back(fmt::format("{}{}.max_{} {:g} (used {:.6g})",
                                o.region.empty() ? "" : o.region + ": ", o.metric, o.stat, o.limit,
                                o.value));
    }
  }
  return out;
}

}  // namespace aosuite::verdict
