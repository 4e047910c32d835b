// What `aosuite tune` searches for one technique: one dimension per number the technique reads
// that the parameter table gives a search range (renderer/params.hpp; a list such as MSSAO's
// level weights is one dimension per weight), a point as coordinates in [0, 1] per dimension,
// and the parameters a point stands for, rounded to three significant digits so that a preset
// file holds exactly what was measured.
#pragma once

#include <string>
#include <vector>

#include "renderer/params.hpp"
#include "renderer/technique.hpp"

namespace aosuite::ao {

struct Dimension {
  const renderer::ParamSpec* spec;
  int element;  // the weight of a list; 0 for a single number
  bool integer;
};

class TuneSpace {
 public:
  // Throws std::invalid_argument when the technique reads no searched parameter.
  explicit TuneSpace(renderer::Technique technique);

  renderer::Technique technique() const { return technique_; }
  const std::vector<Dimension>& dimensions() const { return dims_; }

  // `base` with each dimension set from its coordinate (clamped to [0, 1]).
  renderer::AoParams params(const std::vector<double>& point, renderer::AoParams base) const;
  // The coordinates of `params` (clamped into the search ranges): where a search starts.
  std::vector<double> point(const renderer::AoParams& params) const;
  // `from` moved a share `t` of the way to `to` in the search's coordinates (a log-scaled
  // parameter geometrically): t = 0 is `from` itself, t = 1 is `to`.
  renderer::AoParams between(const renderer::AoParams& from, const renderer::AoParams& to,
                             double t) const;
  // The searched parameters as text, "key=value key=value" in table order: a point's identity
  // (two points that round to the same parameters are the same point).
  std::string key(const renderer::AoParams& params) const;
  // The searched parameters, KEY and VALUE as set_param reads them: what a preset holds.
  std::vector<std::pair<std::string, std::string>> entries(const renderer::AoParams& p) const;

 private:
  renderer::Technique technique_;
  std::vector<Dimension> dims_;
};

}  // namespace aosuite::ao
