#include "page.h"

#include <emscripten.h>

#include "app.h"

namespace {
demo::App* attached = nullptr;
}  // namespace

// Emscripten declares glutIgnoreKeyRepeat but does not define it: a browser
// repeats a held key, and the App takes a repeated space as one press.
extern "C" void glutIgnoreKeyRepeat(int) {}

// The state log (--log-state, which the page always passes) as it is now:
// written for the page's particleDemo.stateLog(), which reads the file. 1 on success.
extern "C" EMSCRIPTEN_KEEPALIVE int particle_demo_write_state_log() {
  return attached && attached->writeStateLog() ? 1 : 0;
}

EM_JS(void, pageFrameDrawn, (), { if (Module.demoFrameDrawn) Module.demoFrameDrawn(); });
EM_JS(void, pageFinished, (int code), { if (Module.demoFinished) Module.demoFinished(code); });

EM_JS(void, pageDownload, (const char* path, const char* type), {
  const name = UTF8ToString(path);
  const data = FS.readFile(name);
  const link = document.createElement('a');
  link.href = URL.createObjectURL(new Blob([data], {type: UTF8ToString(type)}));
  link.download = name.substring(name.lastIndexOf('/') + 1);
  document.body.appendChild(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(link.href), 10000);
});

// The pixels through a 2D canvas, flipped to rows top to bottom, encoded by the browser.
EM_JS(void, pageImage, (const char* path, const unsigned char* rgba, int width, int height), {
  const canvas = document.createElement('canvas');
  canvas.width = width;
  canvas.height = height;
  const context = canvas.getContext('2d');
  const image = context.createImageData(width, height);
  const row = 4 * width;
  for (let y = 0; y < height; ++y)
    image.data.set(HEAPU8.subarray(rgba + (height - 1 - y) * row, rgba + (height - y) * row), y * row);
  context.putImageData(image, 0, 0);
  const name = UTF8ToString(path);
  canvas.toBlob(blob => {
    const link = document.createElement('a');
    link.href = URL.createObjectURL(blob);
    link.download = name.substring(name.lastIndexOf('/') + 1);
    document.body.appendChild(link);
    link.click();
    link.remove();
    setTimeout(() => URL.revokeObjectURL(link.href), 10000);
  }, 'image/png');
});

namespace web {

void attach(demo::App& app) { attached = &app; }
void frameDrawn() { pageFrameDrawn(); }
void finished(int exitCode) { pageFinished(exitCode); }
void offerDownload(const std::string& path, const char* mimeType) { pageDownload(path.c_str(), mimeType); }
void offerImage(const std::string& path, const unsigned char* rgba, int width, int height) {
  pageImage(path.c_str(), rgba, width, height);
}

}  // namespace web
