// What several OpenGL commands share: the options naming a case, and float EXR output.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "ao/case_options.hpp"
#include "renderer/renderer.hpp"
#include "renderer/technique.hpp"

namespace aosuite::cli {

// --scene, --view, --technique, --width, --height, --samples, --radius, --param, --pipeline,
// --gbuffer:
// what `render` and `error` both take.
void add_case_options(CLI::App* cmd, ao::CaseOptions& o);

// --pipeline fragment|compute (renderer::Pipeline) into `pipeline`; left empty when not given.
void add_pipeline_option(CLI::App* cmd, std::string& pipeline);

// A CV_32F single-channel image as float EXR, written atomically; throws FileError.
void write_exr(const std::filesystem::path& path, const cv::Mat& image);

}  // namespace aosuite::cli
