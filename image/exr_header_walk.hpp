// A walk over an EXR file's headers, before OpenEXR reads them, that refuses an attribute
// whose declared size is more than the bytes left in the file.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace aosuite::exr {

// OpenEXR allocates an attribute's declared size before it reads the value, so a tiny file can
// claim gigabytes (exr_fuzz: 35 bytes claiming 1.7 GB). This walks every part's header as
// OpenEXR 3.1 reads it, taking from the file what each attribute type's reader takes (which is
// not always the declared size), and throws std::runtime_error, saying which attribute, when
// a size is more than the bytes left. Where OpenEXR itself would refuse the header the walk may
// stop early or throw: OpenEXR refuses it next, before allocating anything more.
// Returns the attributes' names in file order, every part's (what the walk saw: a test
// compares them with what OpenEXR read).
std::vector<std::string> check_attribute_sizes(const unsigned char* bytes, std::size_t size);

}  // namespace aosuite::exr
