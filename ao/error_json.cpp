#include "ao/error_json.hpp"

#include <cmath>

namespace aosuite::ao {

nlohmann::ordered_json to_json(const reference::ErrorStats& s) {
  return {{"pixels", s.pixels},
          {"rmse", s.rmse},
          {"mae", s.mae},
          {"bias", s.bias},
          {"psnr", s.psnr},
          {"ssim", s.ssim},
          {"noise_floor", s.noise_floor}};
}

nlohmann::ordered_json to_json(const reference::ErrorReport& r) {
  return {{"all", to_json(r.all)}, {"edge", to_json(r.edge)}, {"interior", to_json(r.interior)}};
}

reference::ErrorStats error_stats_from_json(const nlohmann::json& j) {
  reference::ErrorStats s;
  s.pixels = j.at("pixels"), s.rmse = j.at("rmse"), s.mae = j.at("mae"), s.bias = j.at("bias");
  // JSON has no infinity: an exact estimate's PSNR is kept as null (psnr_db's +inf).
  const nlohmann::json& psnr = j.at("psnr");
  s.psnr = psnr.is_null() ? HUGE_VAL : psnr.get<double>();
  s.ssim = j.at("ssim"), s.noise_floor = j.at("noise_floor");
  return s;
}

reference::ErrorReport error_report_from_json(const nlohmann::json& j) {
  return {error_stats_from_json(j.at("all")), error_stats_from_json(j.at("edge")),
          error_stats_from_json(j.at("interior"))};
}

}  // namespace aosuite::ao
