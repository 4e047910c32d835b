// Structure checks for the mesh formats whose assimp 5.2 readers trust their input: a
// truncated binary PLY crashes its reader, a truncated ASCII PLY silently repeats its last
// face, and the OFF reader clamps out-of-range vertex indices. These walk the file's declared
// layout (without decoding geometry) so bad files are refused before assimp sees them.
#pragma once

#include <span>
#include <string_view>
#include <vector>

namespace aosuite::renderer {

// Each throws aosuite::FileError "<name>: <reason>" (with the line for text) when `bytes` are
// not a complete, well-formed file of that format.
void check_ply(std::string_view name, std::span<const unsigned char> bytes);
void check_off(std::string_view name, std::span<const unsigned char> bytes);
// assimp 5.2 skips an OBJ `v`, `vn` or `vt` line it cannot read a number from, so every index
// after it points one vertex further on and a wrong mesh is drawn: each such line must hold its
// numbers (three, or one for `vt`), else this refuses the file with the line.
void check_obj(std::string_view name, std::span<const unsigned char> bytes);

// assimp 5.2 reads a binary PLY's first data byte as a second line end when it is \n and the
// header ends in a bare \n, so every value after it is read one byte late (a valid file refused,
// "index out of range", one in 256 by the first coordinate's low byte). It reads \r\n right:
// this ends such a header so. `bytes` must have passed check_ply.
void mend_ply_header_end(std::string_view name, std::vector<unsigned char>& bytes);

}  // namespace aosuite::renderer
