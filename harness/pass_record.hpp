// Which pass of a rendered case first differs from its golden's: bless keeps, beside each
// golden, the content hash of what each pass wrote when it was made (G-buffer, AO, blur,
// blend); a failing case compares its own and names the first that differs ("gbuffer
// identical; ao differs"), which no image-only tool can say.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace aosuite::harness {

// A render's passes in pipeline order, each with the hash of what it wrote.
using PassHashes = std::vector<std::pair<std::string, std::string>>;

// Where a golden's record lives: <golden's stem>.passes.json beside it.
std::filesystem::path pass_record(const std::filesystem::path& golden);
// The record's bytes (JSON: [[pass, hash], ...]).
std::vector<unsigned char> pass_record_bytes(const PassHashes& passes);
// The record beside `golden`; empty when there is none or it cannot be read (older goldens).
PassHashes read_pass_record(const std::filesystem::path& golden);

// The first pass whose output differs, in words: "ao differs (gbuffer identical)", or
// "every pass identical" when none does; empty when the two name different passes or either is
// empty (nothing to say).
std::string first_differing_pass(const PassHashes& golden, const PassHashes& now);

}  // namespace aosuite::harness
