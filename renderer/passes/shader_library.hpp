// The GLSL sources: embedded at build time, or read from $AOSUITE_SHADER_DIR so a shader can be
// edited and tried (or a regression provoked in a test) without rebuilding.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace aosuite::renderer {

// The text of shader file `name`, e.g. "sao.frag": $AOSUITE_SHADER_DIR/name when that variable
// is set and the file exists there, else the embedded copy. Throws if neither has it.
std::string shader_text(std::string_view name);

// Every embedded shader file name, sorted (what a content hash of "the shaders" covers).
std::vector<std::string_view> shader_names();

// Every shader's name and text as shader_text gives it, as 16 hex digits: what a result
// measured with these shaders depends on (a suite case's input hash, a tune's measurements).
std::string shaders_hash();

}  // namespace aosuite::renderer
