#pragma once
// What the page (particle-demo.html) and the demo say to each other:
// window.particleDemo in the page's script reads the state log and learns
// when the demo has ended; files the demo writes (a scene saved in build
// mode, a screenshot) reach the user as browser downloads.
#include <string>

namespace demo {
class App;
}

namespace web {

// The App that particle_demo_write_state_log() asks (exported to the page).
void attach(demo::App& app);
// A frame was drawn (the page counts them and times the first).
void frameDrawn();
// The demo has ended (q, Esc, --frames) with this exit code.
void finished(int exitCode);
// Offers the file at `path` in Emscripten's in-memory file system to the user
// as a download under its base name.
void offerDownload(const std::string& path, const char* mimeType);
// Offers RGBA pixels (rows bottom to top, as GL reads them) as a PNG download.
void offerImage(const std::string& path, const unsigned char* rgba, int width, int height);

}  // namespace web
