#include "image_file.hpp"

#include <OpenImageIO/imageio.h>

#include <stdexcept>

namespace rc {

void check_image_name(const std::string& path) {
  if (!OIIO::ImageOutput::create(path)) {
    (void)OIIO::geterror();  // clears OpenImageIO's message ("could not find a format writer")
    throw std::runtime_error("cannot write image '" + path +
                             "': no image format for this file name (use .png, .exr, .ppm, ...)");
  }
}

void write_image(const std::string& path, uint32_t width, uint32_t height,
                 const std::vector<uint8_t>& rgb) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error("cannot write image '" + path + "': " + OIIO::geterror());
  const OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 3,
                             OIIO::TypeDesc::UINT8);
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) ||
      !out->close())
    throw std::runtime_error("cannot write image '" + path + "': " + out->geterror());
}

}  // namespace rc
