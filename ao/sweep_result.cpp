#include "ao/sweep_result.hpp"

namespace aosuite::ao {

nlohmann::ordered_json meta_json(const SweepMeta& m) {
  return {{"grid", m.grid},           {"rays", m.rays},
          {"runs", m.runs},           {"gl", m.gl},
          {"gl_device", m.gl_device}, {"pipeline", m.pipeline},
          {"unbounded", m.unbounded}, {"configurations", m.configurations}};
}

}  // namespace aosuite::ao
