// The grid `aosuite sweep` runs: scenes (and views), resolutions, and per technique the
// samples x radius (x intensity) values and any fixed parameters, or a preset (`preset =
// "tuned"` or a file: its values under the table's params, its samples and intensity where the
// table gives no such axis), read from a TOML file (suites/sweep_*.toml).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "renderer/technique.hpp"

namespace aosuite::ao {

struct TechniqueGrid {
  renderer::Technique technique;
  std::vector<int> samples;  // {0} for a technique that takes no sample count
  std::vector<float> radii;
  std::vector<float> intensities;  // empty: the technique's default
  // Other parameters, the same for every configuration (renderer::set_param keys and text).
  std::map<std::string, std::string> params;
};

struct SweepGrid {
  std::string name;
  std::vector<std::string> scenes;  // built-in names or scene files (relative to the grid file)
  std::vector<std::string> views;   // empty: every view of each scene
  std::vector<std::pair<int, int>> resolutions;
  int runs = 3;           // timed runs per configuration after one warm-up; the median is reported
  int rays = 256;         // reference rays per pixel
  bool unbounded = true;  // also measure against the unbounded reference
  std::vector<TechniqueGrid> techniques;
  // Not the grid file's: the command's --pipeline (unset: the device's). It changes the times,
  // not the AO.
  std::optional<renderer::Pipeline> pipeline;
};

// Throws aosuite::FileError naming the file, and the key at fault, for unreadable or bad input.
// `preset`: for every technique table without its own (`sweep --preset`); a file
// there is relative to the grid, so give the command line's as an absolute path.
SweepGrid read_sweep_grid(const std::filesystem::path& path, const std::string& preset = {});

}  // namespace aosuite::ao
