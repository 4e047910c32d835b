#include "ao/sweep_fit.hpp"

#include <map>
#include <tuple>

namespace aosuite::ao {

namespace rd = aosuite::renderer;

nlohmann::ordered_json fit_on_one_view(const std::vector<Row>& rows) {
  using Group = std::tuple<std::string, rd::Technique, int, int>;
  std::map<Group, const Row*> best_fit, best_eval;
  for (const Row& r : rows) {
    const Group key{r.scene, r.technique, r.width, r.height};
    auto& slot = r.view_index == 0 ? best_fit[key] : best_eval[key];
    if (r.view_index <= 1 && (!slot || r.error.all.rmse < slot->error.all.rmse)) slot = &r;
  }
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& [key, fit] : best_fit) {
    const Row* eval = nullptr;
    for (const Row& r : rows) {
      if (r.view_index == 1 && r.scene == fit->scene && r.technique == fit->technique &&
          r.width == fit->width && r.height == fit->height && r.samples == fit->samples &&
          r.radius == fit->radius && r.intensity == fit->intensity)
        eval = &r;
    }
    if (!eval) continue;  // a scene with one view has nothing to evaluate on
    out.push_back({{"scene", fit->scene},
                   {"technique", rd::technique_name(fit->technique)},
                   {"width", fit->width},
                   {"height", fit->height},
                   {"fit_view", fit->view},
                   {"eval_view", eval->view},
                   {"samples", fit->samples},
                   {"radius", fit->radius},
                   {"intensity", fit->intensity},
                   {"rmse_fit_view", fit->error.all.rmse},
                   {"rmse_eval_view", eval->error.all.rmse},
                   {"best_rmse_eval_view", best_eval.at(key)->error.all.rmse}});
  }
  return out;
}

}  // namespace aosuite::ao
