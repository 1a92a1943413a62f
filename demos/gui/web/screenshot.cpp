// The page's screenshots (the k key, --screenshot, --record): the frame as
// the browser encodes it, offered as a download under the file's name (the
// desktop writes PNG files with libpng, which the page does without).
#include "screenshot.h"

#include <vector>

#include "gl_api.h"
#include "page.h"

namespace demo {

std::string writeScreenshot(const std::string& path, int width, int height, const char* /*what: a download cannot fail*/) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(width) * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  web::offerImage(path, pixels.data(), width, height);
  return "";
}

}  // namespace demo
