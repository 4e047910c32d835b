// Writes the differential tests' pairs (tests/metric_pairs.hpp) as files for the reference
// tools: LDR pairs as PNG (what the FLIP tool reads) and as raw RGBA8, HDR pairs as float
// OpenEXR and raw float32 RGB, and manifest.json listing them.
//   metric_oracle_inputs <out-dir> <renders-dir>
//   metric_oracle_inputs --bench <out-dir>    the benchmarks' 1080p and 4K pairs
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "compare/opencv.hpp"
#include "tests/metric_pairs.hpp"

namespace fs = std::filesystem;

static void write_raw(const fs::path& path, const cv::Mat& m) {
  std::ofstream out(path, std::ios::binary);
  for (int y = 0; y < m.rows; ++y)
    out.write(reinterpret_cast<const char*>(m.ptr(y)),
              static_cast<std::streamsize>(m.cols * m.elemSize()));
}

static void write_exr(const fs::path& path, const cv::Mat& m) {
  auto out = OIIO::ImageOutput::create(path.string());
  OIIO::ImageSpec spec(m.cols, m.rows, 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  if (!out || !out->open(path.string(), spec) ||
      !out->write_image(OIIO::TypeDesc::FLOAT, m.ptr<float>()) || !out->close()) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    std::exit(1);
  }
}

int main(int argc, char** argv) {
  if (argc == 3 && std::string(argv[1]) == "--bench") {
    fs::create_directories(argv[2]);
    for (const auto& [w, h] : {std::pair{1920, 1080}, std::pair{3840, 2160}}) {
      for (bool hdr : {false, true}) {
        const auto p = aosuite::test::bench_pair(w, h, hdr);
        const fs::path base = fs::path(argv[2]) / p.name;
        if (hdr) {
          write_exr(base.string() + "_a.exr", p.a), write_exr(base.string() + "_b.exr", p.b);
        } else {
          aosuite::write_png_rgba8(base.string() + "_a.png", p.a);
          aosuite::write_png_rgba8(base.string() + "_b.png", p.b);
        }
      }
    }
    return 0;
  }
  if (argc != 3) {
    std::fprintf(stderr, "usage: metric_oracle_inputs <out-dir> <renders-dir>\n");
    return 2;
  }
  const fs::path dir = argv[1];
  fs::create_directories(dir);
  nlohmann::json manifest = nlohmann::json::array();
  for (const auto& p : aosuite::test::metric_pairs(argv[2])) {
    const std::string ext = p.hdr ? ".exr" : ".png";
    for (int i = 0; i < 2; ++i) {
      const cv::Mat& m = i == 0 ? p.a : p.b;
      const fs::path base = dir / (p.name + (i == 0 ? "_a" : "_b"));
      if (p.hdr) {
        write_exr(base.string() + ext, m);
      } else {
        aosuite::write_png_rgba8(base.string() + ext, m);
      }
      write_raw(base.string() + ".raw", m);
    }
    manifest.push_back({{"name", p.name},
                        {"hdr", p.hdr},
                        {"tone_mapper", p.tone_mapper},
                        {"width", p.a.cols},
                        {"height", p.a.rows}});
  }
  std::ofstream(dir / "manifest.json") << manifest.dump(1) << "\n";
  return 0;
}
