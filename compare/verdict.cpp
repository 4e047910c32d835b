#include "compare/verdict.hpp"

#include <fmt/format.h>

namespace aosuite::verdict {

std::string Verdict::message() const {
  std::string out;
  for (const std::string& f : failed) out += (out.empty() ? "" : "; ") + f;
  return out;
}

Verdict decide(const ResembleFigures* resemble, const ResembleAllowance& allowed,
               std::span<const metric::Outcome> gates) {
  Verdict v;
  if (resemble) {
    if (!resemble->same_size) {
      v.failed.push_back("the images differ in size");
    } else {
      const bool mismatch = resemble->mismatch_percent > allowed.max_mismatch_percent;
      const bool delta = resemble->max_channel_delta > allowed.max_channel_delta;
      if (mismatch || delta) {
        std::string why = fmt::format("mismatch {}% (allowed {}%)", resemble->mismatch_text,
                                      allowed.max_mismatch_percent);
        if (allowed.max_channel_delta < 255) {
          why += fmt::format(", max channel delta {} (allowed {})", resemble->max_channel_delta,
                             allowed.max_channel_delta);
        }
        v.failed.push_back(std::move(why));
      }
    }
  }
  for (const metric::Outcome& o : gates)
    if (!o.pass) v.failed.push_back(o.text());
  v.pass = v.failed.empty();
  return v;
}

}  // namespace aosuite::verdict
