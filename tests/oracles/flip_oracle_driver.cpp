// The FLIP reference: NVlabs/flip v1.6's own code, built from its checkout (never from this
// repository): loads both images as its tool does (stb_image / tinyexr; PNG -> linear sRGB),
// runs FLIP::evaluate and pools with the tool's FLIPPooling::pooling<float>, then prints the
// pooled values with 9 significant digits (the tool prints 6 decimals).
//   g++ -O3 -fopenmp -std=c++17 -I<flip>/src/cpp flip_oracle_driver.cpp -o flip_oracle_driver
//   flip_oracle_driver <reference> <test> [aces|hable|reinhard]
#include <cstdio>
#include <string>

#include "FLIP.h"
#include "tool/imagehelpers.h"
#include "tool/pooling.h"

int main(int argc, char** argv) {
  if (argc < 3) return 2;
  const std::string ref = argv[1], test = argv[2];
  const bool hdr = ref.size() > 4 && ref.substr(ref.size() - 4) == ".exr";
  FLIP::Parameters parameters;
  if (argc > 3) parameters.tonemapper = argv[3];
  FLIP::image<FLIP::color3> r, t;
  if (!ImageHelpers::load(r, ref) || !ImageHelpers::load(t, test)) return 1;
  if (!hdr) {
    r.sRGBToLinearRGB();
    t.sRGBToLinearRGB();
  }
  FLIP::image<float> error(r.getWidth(), r.getHeight(), 0.0f);
  FLIP::image<float> exposure(r.getWidth(), r.getHeight());
  FLIP::evaluate(r, t, hdr, parameters, error, exposure);
  FLIPPooling::pooling<float> pool(100);
  for (int y = 0; y < error.getHeight(); y++)
    for (int x = 0; x < error.getWidth(); x++) pool.update(x, y, error.get(x, y));
  const float median = pool.getPercentile(0.5f, true);
  const float q1 = pool.getPercentile(0.25f, true), q3 = pool.getPercentile(0.75f, true);
  std::printf(
      "{\"mean\": %.9g, \"weighted_median\": %.9g, \"first_weighted_quartile\": %.9g, "
      "\"third_weighted_quartile\": %.9g, \"min\": %.9g, \"max\": %.9g, \"start_exposure\": "
      "%.9g, \"stop_exposure\": %.9g, \"num_exposures\": %d}\n",
      double(pool.getMean()), double(median), double(q1), double(q3), double(pool.getMinValue()),
      double(pool.getMaxValue()), hdr ? double(parameters.startExposure) : 0.0,
      hdr ? double(parameters.stopExposure) : 0.0, hdr ? parameters.numExposures : 0);
  return 0;
}
