// Where goldens live and how they are replaced. A case's folder is <goldens>/<case id>/; in it
// <image>.png is the accepted golden and <image>~<tag>.png are further accepted variants. A
// sub-folder named by a platform key (the GL renderer, e.g. llvmpipe-llvm-15-0-6-256-bits)
// holds goldens for that platform only, and when it has any for an image they replace the
// generic ones there: drivers that rasterise differently get their own goldens.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace aosuite::harness {

// "Mesa | llvmpipe (LLVM 15.0.6, 256 bits) | 4.5 (Core Profile) Mesa 22.3.6" ->
// "llvmpipe-llvm-15-0-6-256-bits": the renderer field, lower case, runs of other characters
// turned into one '-'.
std::string platform_key(std::string_view gl_description);

// The goldens accepted for `image` of a case, platform-specific ones first; empty if none.
std::vector<std::filesystem::path> accepted_goldens(const std::filesystem::path& case_dir,
                                                    std::string_view image,
                                                    std::string_view platform);

// Where `bless` writes: the generic golden, or the platform's when `platform` is not empty,
// as variant `tag` when not empty.
std::filesystem::path golden_path(const std::filesystem::path& case_dir, std::string_view image,
                                  std::string_view platform, std::string_view tag);

// Replaces (or creates) one golden: written beside it under a temporary name, then renamed,
// so a reader or a killed bless sees the old file or the new one, never a mix.
void write_golden(const std::filesystem::path& path, std::span<const unsigned char> png);

}  // namespace aosuite::harness
