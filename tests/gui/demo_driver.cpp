#include "demo_driver.h"

#include <png.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace demotest {

namespace {
std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, separator);) fields.push_back(field);
  return fields;
}
}  // namespace

std::vector<std::string> RunResult::errLines() const {
  std::vector<std::string> lines;
  for (const std::string& line : split(err, '\n'))
    if (!line.empty()) lines.push_back(line);
  return lines;
}

std::string outputDirectory(const std::string& testName) {
  const std::string dir = std::string(TEST_OUTPUT_DIR) + "/" + testName;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

namespace {
RunResult runProgram(const char* program, const std::string& directory, const std::string& args,
                     const std::string& script) {
  std::string command = std::string("cd '") + directory + "' && '" + program + "' " + args;
  if (!script.empty()) {
    std::ofstream(directory + "/script.txt") << script;
    command += " --script script.txt";
  }
  command += " > stdout.txt 2> stderr.txt";
  const int status = std::system(command.c_str());
  RunResult result;
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = readFile(directory + "/stdout.txt");
  result.err = readFile(directory + "/stderr.txt");
  return result;
}
}  // namespace

RunResult runDemo(const std::string& directory, const std::string& args, const std::string& script) {
  return runProgram(PARTICLE_DEMO, directory, args, script);
}

RunResult runParticleLab(const std::string& directory, const std::string& args) {
  return runProgram(PARTICLE_LAB, directory, args, "");
}

demo::Rgb Image::at(int x, int y) const {
  const std::size_t k = (static_cast<std::size_t>(y) * width + x) * 3;
  return {rgb[k], rgb[k + 1], rgb[k + 2]};
}

Image readPng(const std::string& path) {
  FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw std::runtime_error("cannot open " + path);
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(file);
    throw std::runtime_error("libpng failed reading " + path);
  }
  png_init_io(png, file);
  png_read_info(png, info);
  Image image;
  image.width = static_cast<int>(png_get_image_width(png, info));
  image.height = static_cast<int>(png_get_image_height(png, info));
  if (png_get_color_type(png, info) != PNG_COLOR_TYPE_RGB || png_get_bit_depth(png, info) != 8)
    throw std::runtime_error(path + " is not 8-bit RGB");
  image.rgb.resize(static_cast<std::size_t>(image.width) * image.height * 3);
  for (int row = 0; row < image.height; ++row)
    png_read_row(png, image.rgb.data() + static_cast<std::size_t>(row) * image.width * 3, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(file);
  return image;
}

Eigen::Vector2d LoggedPane::toPixel(const Eigen::Vector2d& w) const {
  const double pixelsPerUnit = pixelWidth / (worldMax.x() - worldMin.x());
  return {pixelX + (w.x() - worldMin.x()) * pixelsPerUnit, pixelY + (worldMax.y() - w.y()) * pixelsPerUnit};
}

StateLog readStateLog(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  StateLog log;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> f = split(line, ',');
    // strtod, not stod: a denormal such as a dt of 5e-324 is a valid value.
    auto number = [&](std::size_t k) { return std::strtod(f.at(k).c_str(), nullptr); };
    const std::string& record = f.at(0);
    if (record == "frame") {
      log.frames = std::stoll(f.at(1));
    } else if (record == "paused") {
      log.paused = f.at(1) == "1";
    } else if (record == "pane") {
      LoggedPane p;
      p.scene = f.at(2);
      p.integrator = f.at(3);
      p.dt = number(4);
      p.time = number(5);
      p.steps = std::stoll(f.at(6));
      p.diverged = f.at(7) == "1";
      p.mouseSprings = std::stoi(f.at(8));
      p.energy = number(9);
      p.maxConstraintError = number(10);
      p.mouseSpringEnergy = number(11);
      p.slowMotion = f.at(12) == "1";
      p.substeps = std::stoi(f.at(13));
      p.framesAdvanced = std::stoll(f.at(14));
      p.owedTime = number(15);
      p.plotPoints = std::stoi(f.at(16));
      p.waited = f.at(17) == "1";
      p.longestStepMs = number(18);
      p.framesWaited = std::stoll(f.at(19));
      p.plottedEnergy = number(20);
      p.plottedConstraintError = number(21);
      log.panes.push_back(p);
    } else if (record == "faces") {
      LoggedPane& p = log.panes.at(std::stoul(f.at(1)));
      p.facesShaded = std::stoi(f.at(2));
      p.facesLeftOut = std::stoi(f.at(3));
      p.shadedPixels = number(4);
      p.panePixels = number(5);
      p.spacingPixels = number(6);
      p.springsDrawn = f.at(7) == "1";
      p.particlesDrawn = f.at(8) == "1";
      p.drawnFraction = number(9);
    } else if (record == "text-fit") {
      LoggedOverlay& o = log.overlays.at(log.overlays.size() - 1);
      o.textWidth = std::stoi(f.at(2));
      o.textHeight = std::stoi(f.at(3));
      o.shortened = f.at(4) == "1";
    } else if (record == "budget") {
      LoggedBudget& b = log.budget;
      b.budgetMs = number(1);
      b.steps = std::stoi(f.at(2));
      b.panesStepped = std::stoi(f.at(3));
      b.panesWaiting = std::stoi(f.at(4));
      b.stepOverBudget = f.at(5) == "1";
      b.framesStepped = std::stoll(f.at(8));
      b.framesSpent = std::stoll(f.at(9));
      b.framesWithPaneWaiting = std::stoll(f.at(10));
      b.framesWithStepOverBudget = std::stoll(f.at(11));
    } else if (record == "view") {
      LoggedPane& p = log.panes.at(std::stoul(f.at(1)));
      p.pixelX = std::stoi(f.at(2));
      p.pixelY = std::stoi(f.at(3));
      p.pixelWidth = std::stoi(f.at(4));
      p.pixelHeight = std::stoi(f.at(5));
      p.worldMin = {number(6), number(7)};
      p.worldMax = {number(8), number(9)};
    } else if (record == "particle") {
      LoggedParticle q;
      q.x = {number(3), number(4)};
      q.v = {number(5), number(6)};
      q.mass = number(7);
      q.pinned = f.at(8) == "1";
      log.panes.at(std::stoul(f.at(1))).particles.push_back(q);
    } else if (record == "wall") {
      log.panes.at(std::stoul(f.at(1))).walls.push_back({{number(2), number(3)}, {number(4), number(5)}});
    } else if (record == "grab") {
      LoggedGrab g;
      g.particle = std::stoi(f.at(2));
      g.target = {number(3), number(4)};
      g.stiffness = number(5);
      g.damping = number(6);
      g.framesAveraged = std::stoll(f.at(7));
      g.mean = {number(8), number(9)};
      log.panes.at(std::stoul(f.at(1))).grabs.push_back(g);
    } else if (record == "wind") {
      LoggedWind& w = log.panes.at(std::stoul(f.at(1))).wind;
      w.speed = number(2);
      w.direction = number(3);
      w.drag = number(4);
      w.gust = number(5);
      w.gustPeriod = number(6);
      w.seed = std::stoi(f.at(7));
      w.air = {number(8), number(9)};
    } else if (record == "tearing") {
      LoggedPane& p = log.panes.at(std::stoul(f.at(1)));
      p.tearStrain = number(2);
      p.brokenLinks = std::stoll(f.at(3));
    } else if (record == "overlay" || record == "widget") {
      LoggedOverlay o{f.at(1), std::stoi(f.at(2)), std::stoi(f.at(3)), std::stoi(f.at(4)), std::stoi(f.at(5)), ""};
      for (std::size_t k = 6; k < f.size(); ++k) o.text += (k > 6 ? "," : "") + f[k];
      (record == "overlay" ? log.overlays : log.widgets).push_back(o);
    } else if (record == "frame-times") {
      log.measuredFrames = std::stoll(f.at(1));
      log.medianFrameMs = number(2);
    } else if (record == "real-time") {
      log.realTimeLastSecond = number(1);
      log.realTimeSimSeconds = number(2);
      log.realTimeWallSeconds = number(3);
      log.realTimePaced = f.at(4) == "1";
    } else if (record == "advice") {
      auto field = [&](std::size_t k) { return k < f.size() ? f[k] : std::string(); };
      log.advice.state = f.at(1);
      log.advice.progress = number(2);
      log.advice.integrator = field(3);
      log.advice.dt = number(4);
      log.advice.tolerance = number(5);
      log.advice.framesWhileRunning = std::stoll(f.at(6));
      log.advice.applied = field(7);
    } else if (record == "build") {
      log.build.active = f.at(1) == "1";
      log.build.tool = f.at(2);
      log.build.selection = f.at(3);
      log.build.historyState = std::stoll(f.at(4));
      log.build.historyStates = std::stoll(f.at(5));
      log.build.gesturePoints = std::stoll(f.at(6));
      log.build.grid = number(7);
      for (std::size_t k = 8; k < f.size(); ++k) log.build.file += (k > 8 ? "," : "") + f[k];
    } else if (record == "timing") {
      log.sceneDrawMs = number(1);
      log.overlayDrawMs = number(2);
      log.panelShown = f.at(3) == "1";
    } else {
      throw std::runtime_error("unknown record '" + record + "' in " + path);
    }
  }
  return log;
}

bool near(demo::Rgb a, demo::Rgb b, int tolerance) {
  return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance && std::abs(a.b - b.b) <= tolerance;
}

}  // namespace demotest
