// libaosuite_exr.so's C entry points (image/exr_library.cpp). Only C types cross the
// boundary: image/exr_file.cpp opens the library only when an EXR is read or written.
#pragma once

#include <cstddef>

extern "C" {

// Writes a float image of one channel (Y) or three (R, G, B, interleaved) to `path`. 0 on
// success, else 1 with the reason in err.
int aosuite_write_exr(const char* path, int width, int height, int channels, const float* pixels,
                      char* err, std::size_t err_len);

// Reads an EXR held in memory as float R, G, B (or Y alone), interleaved, over its data window.
// `allocate(user, width, height, channels)` returns room for width * height * channels
// floats, or nullptr to refuse the size (err then names the size; an allocator may keep a
// better reason of its own, as image/exr_file.cpp's does). 0 on success, else 1 with the
// reason in err: a refusal is never silent, whatever the allocator.
int aosuite_read_exr(const unsigned char* bytes, std::size_t size,
                     float* (*allocate)(void* user, int width, int height, int channels),
                     void* user, char* err, std::size_t err_len);
}
