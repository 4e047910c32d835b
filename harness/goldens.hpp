// Where goldens live and how they are replaced. A case's folder is <goldens>/<case id>/; in it
// <image>.png (or .exr, for float images) is the accepted golden and <image>~<tag>.png are
// further accepted variants. A
// sub-folder named by a platform key (the GL renderer, e.g. llvmpipe-llvm-15-0-6-256-bits)
// holds goldens for that platform only: when it has any for an image, its ones replace the
// generic <image>.png there (drivers that rasterise differently get their own goldens) and the
// generic variants <image>~<tag>.png stay accepted after them.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace aosuite::harness {

// "Mesa | llvmpipe (LLVM 15.0.6, 256 bits) | 4.5 (Core Profile) Mesa 22.3.6" ->
// "llvmpipe-llvm-15-0-6-256-bits": the renderer field, lower case, runs of other characters
// turned into one '-'.
std::string platform_key(std::string_view gl_description);

// The goldens accepted for `image` of a case, platform-specific ones first; empty if none.
// Throws std::runtime_error naming the folder when the case's folder (or its platform folder)
// exists but cannot be listed: not a folder, no permission.
// `ext` is the image's file type (".png", ".exr").
std::vector<std::filesystem::path> accepted_goldens(const std::filesystem::path& case_dir,
                                                    std::string_view image, std::string_view ext,
                                                    std::string_view platform);

// An accepted golden as one judgement reads it, once: the judge hash covers these bytes and the
// verdict judges these bytes, so a bless between two reads can never cache a verdict against
// goldens it did not judge. `error` (then no bytes): why it could not be read.
struct ReadGolden {
  std::filesystem::path file;
  std::vector<unsigned char> bytes;
  std::string error;
};
std::vector<ReadGolden> read_goldens(const std::vector<std::filesystem::path>& files);

// Where `bless` writes: the generic golden, or the platform's when `platform` is not empty,
// as variant `tag` when not empty.
std::filesystem::path golden_path(const std::filesystem::path& case_dir, std::string_view image,
                                  std::string_view ext, std::string_view platform,
                                  std::string_view tag);

// Replaces (or creates) a case's goldens all or nothing: every file is first written and
// synced beside its target under a temporary dot-name (.<name>.bless-<pid>-XXXXXX), and only
// when all are written are they renamed into place. On failure before the renames every
// temporary is removed, no golden has changed, and std::runtime_error names the file and the
// reason. A reader or a killed bless sees each golden old or new, never a mix within a file.
using GoldenWrite = std::pair<std::filesystem::path, std::span<const unsigned char>>;
void replace_goldens(const std::vector<GoldenWrite>& files);

// Replaces (or creates) files inside one case's goldens folder `case_dir` (its goldens, variants,
// region maps, platform sub-folders) as one change: a copy of the folder is staged beside it as
// .<case>.bless-<pid>-XXXXXX (unchanged files hard-linked, new ones written and synced), then
// exchanged with the folder in one renameat2(RENAME_EXCHANGE), and the old copy removed. A
// reader, a killed bless or a second bless racing this one sees the case all old or all new,
// never a mix of files. On failure before the exchange the staged copy is removed, nothing has
// changed, and std::runtime_error names the file and the reason. Every path in `files` must be
// inside case_dir.
void replace_case_goldens(const std::filesystem::path& case_dir,
                          const std::vector<GoldenWrite>& files);

// Removes temporaries a killed bless left in `case_dir` and its platform folders, and the
// staged or replaced copies of the case beside it: ours whose process is gone, and the older
// form .<name>.tmp-XXXXXX once a minute old. Returns how many.
int remove_stale_temporaries(const std::filesystem::path& case_dir);

}  // namespace aosuite::harness
