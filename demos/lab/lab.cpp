#include "lab/lab.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "output_file.h"
#include "particles/forces/gravity.h"

namespace lab {

using particles::ParticleSystem;

double gravityMagnitude(const ParticleSystem& system) {
  for (const auto& force : system.forceObjects())
    if (auto* gravity = dynamic_cast<const particles::GravityForce*>(force.get()))
      return gravity->acceleration().norm();
  return 0.0;
}

double energyScale(const ParticleSystem& system) {
  const int n = system.size();
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  double movingMass = 0.0;
  for (int i = 0; i < n; ++i) {
    lo = lo.cwiseMin(system.position(i));
    hi = hi.cwiseMax(system.position(i));
    if (!system.pinned(i)) movingMass += system.masses()[i];
  }
  const double diagonal = n > 0 ? (hi - lo).norm() : 0.0;
  return movingMass * gravityMagnitude(system) * diagonal + std::abs(system.totalEnergy()) + 1.0;
}

particles::DivergenceLimits Explosion::limits(const ParticleSystem& system) const {
  particles::DivergenceLimits limits;
  limits.maxRelativeConstraintError = maxRelativeStretch;
  limits.energyScale = energyScale(system);
  limits.energyRiseFraction = energyGain;
  return limits;
}

RunResult simulate(scenes::Scene& scene, particles::Integrator& integrator, double dt,
                   double duration, const Explosion& explosion,
                   const std::function<void(const ParticleSystem&)>& observe) {
  ParticleSystem& system = *scene.system;
  RunResult result;
  result.energyStart = system.totalEnergy();
  const particles::DivergenceLimits limits = explosion.limits(system);
  const long steps = std::lround(duration / dt);
  using Clock = std::chrono::steady_clock;
  for (long k = 0; k < steps && !interrupted(); ++k) {
    const auto start = Clock::now();
    const particles::StepStats stats = system.step(integrator, dt);
    result.seconds += std::chrono::duration<double>(Clock::now() - start).count();
    ++result.steps;
    result.time = system.time();
    result.work += stats;
    if (system.finite())
      result.maxRelativeStretch = std::max(result.maxRelativeStretch, system.maxRelativeConstraintError());
    if (const particles::Divergence d = particles::checkDivergence(system, limits, result.energyStart, stats)) {
      result.exploded = true;
      result.reason = particles::divergenceReasonName(d.reason);
      break;
    }
    if (observe) observe(system);
  }
  result.energyEnd = system.totalEnergy();
  return result;
}

std::vector<std::string> selectedIntegrators(const LabOptions& options) {
  std::vector<std::string> names;
  for (const auto& info : particles::integratorTable())
    if (options.integrators.empty() ||
        std::find(options.integrators.begin(), options.integrators.end(), info.name) !=
            options.integrators.end())
      names.push_back(info.name);
  for (const auto& name : options.integrators) particles::makeIntegrator(name);  // rejects unknown
  return names;
}

double bisectStep(const std::function<bool(double)>& survives, double lo, double hi, int rounds) {
  if (survives(hi)) return hi;
  bool found = false;
  const double bottom = lo;
  for (int k = 0; k < rounds && !interrupted(); ++k) {
    const double mid = std::sqrt(lo * hi);
    if (survives(mid)) {
      lo = mid;
      found = true;
    } else {
      hi = mid;
    }
  }
  if (interrupted()) return 0.0;  // cut short: the caller discards it
  if (!found) return survives(bottom) ? bottom : 0.0;
  return lo;
}

double maxStableStep(const std::function<scenes::Scene()>& build, const std::string& integrator,
                     double duration, double lo, double hi, int rounds, const Explosion& explosion,
                     Progress& progress) {
  return bisectStep(
      [&](double dt) {
        scenes::Scene scene = build();
        auto stepper = particles::makeIntegrator(integrator);
        progress.tick();
        return !simulate(scene, *stepper, dt, duration, explosion).exploded;
      },
      lo, hi, rounds);
}

std::vector<double> logSpace(double lo, double hi, int count) {
  std::vector<double> values(count);
  for (int k = 0; k < count; ++k)
    values[k] = count == 1 ? lo : lo * std::pow(hi / lo, static_cast<double>(k) / (count - 1));
  return values;
}

double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (!(x[k] > 0.0) || !(y[k] > 0.0) || !std::isfinite(y[k])) continue;
    const double lx = std::log(x[k]), ly = std::log(y[k]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, ++n;
  }
  if (n < 2) return std::nan("");
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

Csv::Csv(const std::string& path, const std::vector<std::string>& columns)
    : path_(path), out_(path), columns_(columns.size()) {
  if (!out_) throw std::runtime_error("cannot write " + path);
  for (std::size_t k = 0; k < columns.size(); ++k) out_ << (k ? "," : "") << columns[k];
  out_ << '\n' << std::flush;
  if (!out_) scenes::throwWriteError("the CSV", path_);
}

Csv& Csv::operator<<(const std::string& cell) {
  out_ << (cell_++ ? "," : "") << cell;
  return *this;
}

Csv& Csv::operator<<(double value) {
  std::ostringstream s;
  s.precision(10);
  s << value;
  return *this << s.str();
}

Csv& Csv::operator<<(long value) { return *this << std::to_string(value); }

void Csv::endRow() {
  if (cell_ != columns_)
    throw std::logic_error(path_ + ": row has " + std::to_string(cell_) + " cells, expected " +
                           std::to_string(columns_));
  out_ << '\n' << std::flush;
  if (!out_) scenes::throwWriteError("the CSV", path_);
  cell_ = 0;
}

void prepareOutput(const LabOptions& options) { std::filesystem::create_directories(options.outDir); }

void writeTable(const LabOptions& options, const std::string& name, const std::string& title,
                const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  std::ostringstream md;
  md << "*" << title << "*\n\n";
  auto line = [&](const std::vector<std::string>& cells) {
    md << '|';
    for (const auto& c : cells) md << ' ' << c << " |";
    md << '\n';
  };
  line(header);
  md << '|';
  for (std::size_t k = 0; k < header.size(); ++k) md << (k ? " ---: |" : " --- |");
  md << '\n';
  for (const auto& row : rows) line(row);
  const std::string path = options.outDir + "/" + name + ".md";
  std::ofstream out(path);
  out << md.str();
  out.close();
  if (!out) scenes::throwWriteError("the table", path);
  std::cout << "\n" << md.str() << std::flush;
}

void recordValue(const LabOptions& options, const std::string& key, const std::string& value) {
  const std::string path = options.outDir + "/values.csv";
  std::map<std::string, std::string> values;
  {
    std::ifstream in(path);
    std::string row;
    while (std::getline(in, row)) {
      const auto comma = row.find(',');
      if (comma != std::string::npos && row.substr(0, comma) != "key")
        values[row.substr(0, comma)] = row.substr(comma + 1);
    }
  }
  values[key] = value;
  std::ofstream out(path);
  out << "key,value\n";
  for (const auto& [k, v] : values) out << k << ',' << v << '\n';
  out.close();
  if (!out) scenes::throwWriteError("the values", path);
}

std::string fixed(double value, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << value;
  return s.str();
}

std::string general(double value, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << value;
  return s.str();
}

Progress::Progress(std::string label, long total)
    : label_(std::move(label)), total_(total), start_(std::chrono::steady_clock::now()), lastPrint_(start_) {}

void Progress::tick(long count) {
  done_ += count;
  const auto now = std::chrono::steady_clock::now();
  if (now - lastPrint_ < std::chrono::seconds(2) && done_ < total_) return;
  lastPrint_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double left = done_ > 0 ? elapsed * (total_ - done_) / done_ : 0.0;
  std::fprintf(stderr, "[%s] %ld/%ld done, %.0f s elapsed, ~%.0f s left\n", label_.c_str(), done_,
               total_, elapsed, left);
}

Progress::~Progress() {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "[%s] finished %ld/%ld in %.1f s\n", label_.c_str(), done_, total_, elapsed);
}

namespace {
std::atomic<bool> stopRequested{false};
extern "C" void onInterrupt(int) { stopRequested = true; }
}  // namespace

void installInterruptHandler() {
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
}

bool interrupted() { return stopRequested.load(); }

}  // namespace lab
