#pragma once
#include <string>

namespace demo {

// Reads the back buffer (width × height, the whole window) and writes it as an
// 8-bit RGB PNG, top row first. Returns an error message naming the file as
// `what` ("--screenshot", "--record", "the k key's screenshot"), empty on success.
std::string writeScreenshot(const std::string& path, int width, int height, const char* what);

}  // namespace demo
