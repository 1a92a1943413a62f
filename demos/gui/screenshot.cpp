#include "screenshot.h"

#include <GL/gl.h>
#include <png.h>

#include <ostream>
#include <stdexcept>
#include <vector>

#include "output/output_file.h"

namespace demo {

std::string writeScreenshot(const std::string& path, int width, int height, const char* what) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());

  try {
    output::OutputFile file(path, what);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info || setjmp(png_jmpbuf(png))) {
      png_destroy_write_struct(&png, &info);
      throw output::WriteError("libpng failed writing '" + path + "'");  // the partial file is removed
    }
    // libpng writes through the output file's stream (checked on close).
    const auto write = [](png_structp p, png_bytep data, png_size_t size) {
      static_cast<std::ostream*>(png_get_io_ptr(p))->write(reinterpret_cast<const char*>(data),
                                                           static_cast<std::streamsize>(size));
    };
    const auto flush = [](png_structp p) { static_cast<std::ostream*>(png_get_io_ptr(p))->flush(); };
    png_set_write_fn(png, &file.stream(), write, flush);
    png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    // GL's rows run bottom to top, PNG's top to bottom.
    for (int row = height - 1; row >= 0; --row)
      png_write_row(png, pixels.data() + static_cast<std::size_t>(row) * width * 3);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    file.close();
    return "";
  } catch (const std::exception& e) {  // cannot open (std::invalid_argument) or write (output::WriteError)
    return e.what();
  }
}

}  // namespace demo
