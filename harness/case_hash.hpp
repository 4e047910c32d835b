// Content hashes that decide whether a case must be rendered or judged again.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "harness/suite.hpp"

namespace aosuite::harness {

// Everything a render depends on: the renderer's build (the bytes of the library holding this
// code), every shader's text as the renderer will read it, the scene's geometry, colours and
// views, the view, technique, parameters, size and the GL implementation.
std::string input_hash(const Case& c, const std::string& gl_description);

// What an image case's images depend on: its command (before {out} is filled in), fields and
// params, and the bytes of the files it declares as inputs; for files on disk, their bytes.
std::string image_input_hash(const Case& c);

// Everything a verdict depends on besides the render: the accepted goldens' bytes and names,
// the tolerance and its mask image.
std::string judge_hash(const Case& c, const std::string& input_hash,
                       const std::vector<std::vector<std::filesystem::path>>& goldens);

}  // namespace aosuite::harness
