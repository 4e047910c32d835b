// Content hashes that decide whether a case must be rendered or judged again.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "harness/goldens.hpp"
#include "harness/suite.hpp"

namespace aosuite::harness {

// What an image case's images depend on: its command (before {out} is filled in), fields and
// params, the bytes of its program and of every argument naming a file, the values of the
// environment variables it declares (`env`) and the bytes of the files it declares as inputs;
// for files on disk, their bytes.
std::string image_input_hash(const Case& c);

// Everything a verdict depends on besides the render: the accepted goldens' bytes and names,
// the tolerance and its mask image.
std::string judge_hash(const Case& c, const std::string& input_hash,
                       const std::vector<std::vector<ReadGolden>>& goldens);

}  // namespace aosuite::harness
