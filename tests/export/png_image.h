#pragma once
// Reading a PNG (a browser screenshot) into RGBA8 pixels with libpng's simplified API, for the
// viewer's browser test.
#include <png.h>

#include <cstdint>
#include <string>
#include <vector>

namespace windplan::test {

struct RgbaImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  ///< row-major, 4 bytes per pixel
  const std::uint8_t* at(int x, int y) const { return &rgba[4 * (std::size_t(y) * width + x)]; }
};

/// \return false (and `why`) when the file cannot be read as a PNG.
inline bool read_png(const std::string& path, RgbaImage* img, std::string* why) {
  png_image im{};
  im.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&im, path.c_str())) {
    *why = path + ": " + im.message;
    return false;
  }
  im.format = PNG_FORMAT_RGBA;
  img->width = static_cast<int>(im.width);
  img->height = static_cast<int>(im.height);
  img->rgba.assign(PNG_IMAGE_SIZE(im), 0);
  if (!png_image_finish_read(&im, nullptr, img->rgba.data(), 0, nullptr)) {
    *why = path + ": " + im.message;
    png_image_free(&im);
    return false;
  }
  return true;
}

}  // namespace windplan::test
