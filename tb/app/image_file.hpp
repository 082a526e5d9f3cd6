// Image files through OpenImageIO, for the raycore command only: the libraries and the tests do
// not link OpenImageIO (its dependencies, some 250 shared libraries, cost every process that
// loads them about half a second of start-up).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rc {

// Writes rgb (8 bits per channel, top row first) in the format the file name names (PNG, EXR,
// PPM, ...). Throws std::runtime_error naming the file when it cannot.
void write_image(const std::string& path, uint32_t width, uint32_t height,
                 const std::vector<uint8_t>& rgb);
// Throws std::runtime_error when OpenImageIO has no writer for the file name's extension, before
// any work (creates no file).
void check_image_name(const std::string& path);

}  // namespace rc
