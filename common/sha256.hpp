// SHA-256 (FIPS 180-4), for files pinned by the checksum `sha256sum` prints: scene files pin
// their meshes with it. Self-contained because nothing the project links provides one.
#pragma once

#include <span>
#include <string>

namespace aosuite {

// The digest of `bytes` as 64 lowercase hex digits, as `sha256sum` prints it.
std::string sha256_hex(std::span<const unsigned char> bytes);

}  // namespace aosuite
