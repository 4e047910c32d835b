#include "ao/sweep_tables.hpp"

#include <fmt/format.h>

#include <cmath>

namespace aosuite::ao {

namespace rd = aosuite::renderer;
namespace ref = aosuite::reference;

std::string sweep_csv(const std::vector<Row>& rows, bool unbounded) {
  std::string out =
      "scene,view,technique,width,height,samples,radius,intensity,ao_gl_ms,pixels,rmse,"
      "mae,bias,psnr,ssim,noise_floor,edge_rmse,interior_rmse,rmse_unbounded,bias_unbounded,"
      "ssim_unbounded,";
  for (const metric::Metric* m : metric::all()) out += fmt::format("frame_{},", m->name);
  out += "params\n";
  for (const Row& r : rows) {
    const ref::ErrorStats& a = r.error.all;
    out += fmt::format(
        "{},{},{},{},{},{},{:g},{:g},{:.3f},{},{:.6f},{:.6f},{:.6f},{:.4f},{:.6f},{:.6f},{:."
        "6f},{:.6f}",
        r.scene, r.view, rd::technique_name(r.technique), r.width, r.height, r.samples, r.radius,
        r.intensity, r.gl_ms, a.pixels, a.rmse, a.mae, a.bias, a.psnr, a.ssim, a.noise_floor,
        r.error.edge.rmse, r.error.interior.rmse);
    out += unbounded ? fmt::format(",{:.6f},{:.6f},{:.6f}", r.unbounded.rmse, r.unbounded.bias,
                                   r.unbounded.ssim)
                     : ",,,";
    for (const metric::Value& v : r.frame.values)  // an infinite PSNR (no difference): empty
      out += std::isfinite(v.value) ? fmt::format(",{:.6f}", v.value) : std::string(",");
    // Quoted: list values hold commas.
    out += r.params.empty() ? ",\n" : fmt::format(",\"{}\"\n", params_text(r));
  }
  return out;
}

std::string sweep_markdown(const std::vector<Row>& rows, const nlohmann::ordered_json& fit,
                           bool unbounded) {
  std::string md =
      "| scene | view | technique | size | s | r | k | AO ms | RMSE | noise | bias | SSIM | edge "
      "RMSE "
      "| interior RMSE | RMSE unbounded | frame FLIP | frame SSIM "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";  // the CSV has
                                                                                     // every metric
  for (const Row& r : rows) {
    const ref::ErrorStats& a = r.error.all;
    md += fmt::format(
        "| {} | {} | {} | {}×{} | {} | {:g} | {:g} | {:.1f} | {:.4f} | {:.4f} | {:+.4f} | "
        "{:.3f} | {:.4f} | {:.4f} | {} | {:.4f} | {:.4f} |\n",
        r.scene, r.view, row_label(r), r.width, r.height, r.samples, r.radius, r.intensity, r.gl_ms,
        a.rmse, a.noise_floor, a.bias, a.ssim, r.error.edge.rmse, r.error.interior.rmse,
        unbounded ? fmt::format("{:.4f}", r.unbounded.rmse) : "–", r.frame.value("flip"),
        r.frame.value("ssim"));
  }
  md +=
      "\n| scene | technique | size | fitted on | s | r | k | RMSE there | evaluated on | RMSE "
      "there | best RMSE there |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& f : fit) {
    md +=
        fmt::format("| {} | {} | {}×{} | {} | {} | {:g} | {:g} | {:.4f} | {} | {:.4f} | {:.4f} |\n",
                    f["scene"].get<std::string>(), f["technique"].get<std::string>(),
                    f["width"].get<int>(), f["height"].get<int>(), f["fit_view"].get<std::string>(),
                    f["samples"].get<int>(), f["radius"].get<float>(), f["intensity"].get<float>(),
                    f["rmse_fit_view"].get<double>(), f["eval_view"].get<std::string>(),
                    f["rmse_eval_view"].get<double>(), f["best_rmse_eval_view"].get<double>());
  }
  return md;
}

}  // namespace aosuite::ao
