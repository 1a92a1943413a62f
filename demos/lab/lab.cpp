#include "lab/lab.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <thread>

#include "lab/cells.h"
#include "particles/cancel.h"
#include "particles/threads.h"
#include "lab/lab_scene.h"
#include "lab/values.h"
#include "output/output_file.h"
#include "particles/forces/gravity.h"

namespace lab {

using particles::ParticleSystem;

double gravityMagnitude(const ParticleSystem& system) {
  for (const auto& force : system.forceObjects())
    if (auto* gravity = dynamic_cast<const particles::GravityForce*>(force.get()))
      return gravity->acceleration().norm();
  return 0.0;
}

// The CPUs this process may run on (its affinity mask: taskset, Slurm), not the machine's.
int defaultJobs() { return particles::affinityCpuCount(); }

RunResult simulate(scenes::Scene& scene, particles::Integrator& integrator, double dt,
                   double duration, const FailureCriterion& criterion,
                   const std::function<bool(const ParticleSystem&)>& observe,
                   const std::vector<double>& checkpoints) {
  ParticleSystem& system = *scene.system;
  RunResult result;
  result.energyStart = system.totalEnergy();
  result.energyScale = releasableEnergy(system);
  const long steps = std::lround(duration / dt);
  // An infinite threshold switches that test off (the engine's convention).
  const particles::DivergenceLimits limits = divergenceLimits(criterion, result.energyScale);
  using Clock = std::chrono::steady_clock;
  auto fail = [&](Failure failure) {
    result.failed = true;
    result.failure = failure;
    result.reason = failureName(failure);
  };
  for (long k = 0; k < steps; ++k) {
    if (interrupted()) {
      result.cutShort = true;
      break;
    }
    const auto start = Clock::now();
    particles::StepStats stats;
    try {
      stats = system.step(integrator, dt);
    } catch (const std::exception&) {
      result.seconds += std::chrono::duration<double>(Clock::now() - start).count();
      ++result.steps;
      result.time = k * dt + dt;
      fail(Failure::StepFailed);
      break;
    }
    if (interrupted()) {  // the step's solves may have been cut short: not a result
      result.cutShort = true;
      break;
    }
    result.seconds += std::chrono::duration<double>(Clock::now() - start).count();
    ++result.steps;
    result.time = system.time();
    result.work += stats;
    if (system.finite()) {
      result.maxRelativeStretch = std::max(result.maxRelativeStretch, system.maxRelativeConstraintError());
      const double rise = (system.totalEnergy() - result.energyStart) / result.energyScale;
      if (std::isfinite(rise)) result.maxEnergyRise = std::max(result.maxEnergyRise, rise);
    }
    for (std::size_t c = result.maximaAt.size(); c < checkpoints.size() && result.time >= checkpoints[c] - 0.5 * dt;
         ++c)
      result.maximaAt.push_back({checkpoints[c], result.maxRelativeStretch, result.maxEnergyRise});
    const Failure failure = checkFailure(system, limits, result.energyStart, stats);
    if (failure != Failure::None) {
      fail(failure);
      break;
    }
    if (observe && !observe(system)) {
      result.stopped = true;
      break;
    }
  }
  result.energyEnd = system.totalEnergy();
  return result;
}

std::optional<Probe> runMember(const std::function<scenes::Scene()>& build, const std::string& integrator,
                               double dt, int member, double duration, const FailureCriterion& criterion,
                               const std::atomic<bool>* cancel, const std::vector<double>& checkpoints) {
  scenes::Scene scene = build();
  perturbStart(scene, member);
  auto stepper = particles::makeIntegrator(integrator);
  std::function<bool(const particles::ParticleSystem&)> carryOn;
  if (cancel) carryOn = [cancel](const particles::ParticleSystem&) { return !cancel->load(); };
  const RunResult r = simulate(scene, *stepper, dt, duration, criterion, carryOn, checkpoints);
  if (r.cutShort || r.stopped) return std::nullopt;
  Probe p;
  p.failed = r.failed;
  p.failure = r.failure;
  p.time = r.time;
  p.maxRelativeStretch = r.maxRelativeStretch;
  p.maxEnergyRise = r.maxEnergyRise;
  p.maximaAt = r.maximaAt;
  return p;
}

std::optional<Boundary> scanSafeStep(const std::function<scenes::Scene()>& build, const std::string& integrator,
                                     double duration, ScanSettings settings, const FailureCriterion& criterion) {
  settings.durations = {duration};
  const double ratio = settings.grid.size() > 1 ? settings.grid[1] / settings.grid[0] : 1.05;
  for (int extension = 0;; ++extension) {
    const auto runs = scanSteps(
        [&](double dt, int member, double T) { return runMember(build, integrator, dt, member, T, criterion); },
        settings);
    if (!runs) return std::nullopt;
    const Boundary b = boundaryOf(survivalAt(*runs, duration, settings.members));
    if (!b.belowGrid() || extension >= settings.extendDecades) return b;
    // The same grid continued a decade further down.
    std::vector<double> lower;
    for (double dt = settings.grid.front() / ratio; dt >= 0.1 * settings.grid.front() * (1 - 1e-9); dt /= ratio)
      lower.insert(lower.begin(), dt);
    settings.grid.insert(settings.grid.begin(), lower.begin(), lower.end());
  }
}

std::string safeStepText(const Boundary& b) {
  if (b.belowGrid()) return "< " + general(b.lowest, 2);
  if (b.aboveGrid()) return "≥ " + general(b.highest, 2);
  return general(b.safeDt, 2);
}

// RATTLE's projections are solved by CG, about m iterations each on a chain
// of m rods: 75x a Verlet step on the 80-rod chain, so the sweeps over chains
// of up to 1000 particles leave it out until it uses the direct solve.
bool inLabSweeps(const std::string& scheme) { return scheme != "rattle"; }

std::vector<std::string> selectedIntegrators(const LabOptions& options, bool everyScheme) {
  std::vector<std::string> names;
  for (const auto& info : particles::integratorTable())
    if ((options.integrators.empty() && (everyScheme || inLabSweeps(info.name))) ||
        std::find(options.integrators.begin(), options.integrators.end(), info.name) !=
            options.integrators.end())
      names.push_back(info.name);
  for (const auto& name : options.integrators) particles::requireIntegrator(name);  // rejects unknown
  return names;
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

Csv::Csv(const LabOptions& options, const std::string& name, const std::vector<std::string>& columns) {
  if (options.cells->writesOutputs())
    writer_ = std::make_unique<output::CsvWriter>(options.outDir + "/" + name, "the CSV", columns,
                                                  output::CsvFormat{10, true});
}

Csv::~Csv() = default;

Csv& Csv::operator<<(const std::string& cell) {
  if (writer_) *writer_ << cell;
  return *this;
}

Csv& Csv::operator<<(double value) {
  if (writer_) *writer_ << value;
  return *this;
}

Csv& Csv::operator<<(long value) {
  if (writer_) *writer_ << value;
  return *this;
}

void Csv::endRow() {
  if (writer_) writer_->endRow();
}

void createOutputDirectory(const std::string& dir) {
  if (dir.empty()) throw std::invalid_argument("--out: expected a directory name, got an empty one");
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (!error && !std::filesystem::is_directory(dir, error)) error = std::make_error_code(std::errc::not_a_directory);
  if (error) throw std::invalid_argument("--out: cannot create the directory '" + dir + "': " + error.message());
}

void prepareOutput(const LabOptions& options, const std::string& valuePrefix) {
  if (!options.cells->writesOutputs()) return;  // a shard made its directory for its cells
  createOutputDirectory(options.outDir);
  removeValues(options.outDir, valuePrefix);
}

void writeTable(const LabOptions& options, const std::string& name, const std::string& title,
                const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  if (!options.cells->writesOutputs()) return;
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
  output::OutputFile out(path, "the table");
  out.stream() << md.str();
  out.close();
  std::cout << "\n" << md.str() << std::flush;
}

void recordValue(const LabOptions& options, const std::string& key, const std::string& value) {
  if (options.cells->writesOutputs()) writeValue(options.outDir, key, value);
}

Progress::Progress(const LabOptions& options, std::string label, long total)
    : label_(std::move(label)),
      total_(total),
      cells_(options.cells.get()),
      silent_(options.cells->mode() == Cells::Mode::Replay),
      start_(std::chrono::steady_clock::now()),
      lastPrint_(start_) {
  // A shard says which it is, and ends with the count of its own cells.
  if (options.cells->mode() == Cells::Mode::Shard)
    label_ += " shard " + std::to_string(options.cells->shard().index) + "/" +
              std::to_string(options.cells->shard().count);
}

void Progress::tick(long count) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (silent_) return;
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
  if (silent_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (cells_->mode() == Cells::Mode::Shard)
    std::fprintf(stderr, "[%s] finished in %.1f s: %ld of its %ld cells recorded (of %zu in the sweep)\n",
                 label_.c_str(), elapsed, cells_->recorded(), cells_->shardShare(), cells_->count());
  else
    std::fprintf(stderr, "[%s] finished %ld/%ld in %.1f s\n", label_.c_str(), done_, total_, elapsed);
}

namespace {
std::atomic<bool> stopRequested{false};
extern "C" void onInterrupt(int) { stopRequested = true; }
}  // namespace

void installInterruptHandler() {
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  std::signal(SIGHUP, onInterrupt);  // the terminal closed: stop as for SIGTERM, outputs complete
  particles::setCancelFlag(&stopRequested);  // and a long solve inside a step stops too
}

bool interrupted() { return stopRequested.load(); }

}  // namespace lab
