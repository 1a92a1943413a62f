// Islands and sleep (islands.h).
#include "islands.h"

#include <algorithm>
#include <numeric>

namespace particles {

namespace {

int findRoot(std::vector<int>& parent, int a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

// Islands are looked for at most this often once some particle has rested
// long enough (a hanging cloth at rest, touching nothing, never sleeps, and
// costs a union–find of its springs only this often).
constexpr double kIslandInterval = 0.1;  // s

}  // namespace

const Eigen::VectorXd& Islands::inverseMasses(const Eigen::VectorXd& w) const {
  if (sleeping_ == 0) return w;
  effective_ = w;
  for (std::size_t i = 0; i < asleep_.size(); ++i)
    if (asleep_[i]) effective_[static_cast<Eigen::Index>(i)] = 0.0;
  return effective_;
}

void Islands::hold(Eigen::VectorXd& x, Eigen::VectorXd& v) const {
  if (sleeping_ == 0) return;
  for (std::size_t i = 0; i < asleep_.size(); ++i)
    if (asleep_[i]) {
      x.segment<2>(2 * i) = held_.segment<2>(2 * i);
      v.segment<2>(2 * i).setZero();
    }
}

void Islands::wakeAll() {
  std::fill(asleep_.begin(), asleep_.end(), 0);
  std::fill(group_.begin(), group_.end(), -1);
  std::fill(rested_.begin(), rested_.end(), 0.0);
  sleeping_ = 0;
}

void Islands::wake(int particle) {
  // Its island: every particle that fell asleep with it.
  const int group = group_[particle];
  for (std::size_t p = 0; p < group_.size(); ++p) {
    if (group_[p] != group) continue;
    group_[p] = -1;
    asleep_[p] = 0;
    rested_[p] = 0.0;
    --sleeping_;
  }
}

// The constraint and force links between moving particles, and the particles
// a time-dependent force or a mouse joint (a force on one particle alone)
// acts on.
void Islands::buildLinks(const SleepScene& scene, int n) {
  links_.clear();
  keptAwake_.assign(n, 0);
  const auto join = [&](const std::vector<int>& ps) {
    for (std::size_t k = 1; k < ps.size(); ++k) links_.emplace_back(ps[0], ps[k]);
  };
  for (const auto& c : scene.constraints) join(c->particles());
  for (const auto& f : scene.forces) {
    const std::vector<int> ps = f->particles();
    if (f->timeDependent() || ps.size() == 1)
      for (int p : ps) keptAwake_[p] = 1;
    join(ps);
  }
  structure_ = scene.structure;
}

// Union–find over the links and the contacts; island_[p] labels p's island,
// members_ lists each island's particles.
void Islands::findIslands(const SleepScene& scene, int n) {
  const Eigen::VectorXd& w = scene.inverseMass;
  parent_.resize(n);
  std::iota(parent_.begin(), parent_.end(), 0);
  const auto unite = [&](int a, int b) {
    if (w[a] == 0.0 || w[b] == 0.0) return;  // a pin joins nothing
    const int ra = findRoot(parent_, a), rb = findRoot(parent_, b);
    if (ra != rb) parent_[ra] = rb;
  };
  for (const auto& [a, b] : links_) unite(a, b);
  for (const Contact& c : scene.contacts)
    if (c.count() == 2) unite(c.particle[0], c.particle[1]);
  island_.assign(n, -1);
  int islands = 0;
  for (int p = 0; p < n; ++p) {
    const int root = findRoot(parent_, p);
    if (island_[root] < 0) island_[root] = islands++;
    island_[p] = island_[root];
  }
  memberStart_.assign(islands + 1, 0);
  for (int p = 0; p < n; ++p) ++memberStart_[island_[p] + 1];
  for (int i = 0; i < islands; ++i) memberStart_[i + 1] += memberStart_[i];
  members_.resize(n);
  std::vector<int> fill(memberStart_.begin(), memberStart_.end() - 1);
  for (int p = 0; p < n; ++p) members_[fill[island_[p]]++] = p;
}

void Islands::update(const SleepScene& scene, const ContactSettings& settings, const Eigen::VectorXd& x,
                     const Eigen::VectorXd& v, double dt) {
  const int n = static_cast<int>(scene.inverseMass.size());
  if (static_cast<int>(asleep_.size()) != n || scene.structure != structure_) {
    asleep_.assign(n, 0);
    group_.assign(n, -1);
    rested_.assign(n, 0.0);
    sleeping_ = 0;
    buildLinks(scene, n);
    sinceIslands_ = kIslandInterval;
  }
  if (!(settings.sleepTime > 0.0)) {
    if (sleeping_ > 0) wakeAll();
    return;
  }
  // Wake what an awake particle touched.
  if (sleeping_ > 0)
    for (const Contact& c : scene.contacts)
      if (c.count() == 2 && asleep_[c.particle[0]] != asleep_[c.particle[1]])
        wake(asleep_[c.particle[0]] ? c.particle[0] : c.particle[1]);
  // Rest times.
  bool rested = false;
  const double slow = settings.sleepSpeed * settings.sleepSpeed;
  for (int p = 0; p < n; ++p) {
    if (asleep_[p] || scene.inverseMass[p] == 0.0) continue;
    rested_[p] = v.segment<2>(2 * p).squaredNorm() < slow ? rested_[p] + dt : 0.0;
    rested = rested || rested_[p] >= settings.sleepTime;
  }
  sinceIslands_ += dt;
  if (!rested || sinceIslands_ < kIslandInterval) return;
  sinceIslands_ = 0.0;
  findIslands(scene, n);
  // An island sleeps when every moving particle of it rested long enough, it
  // touches something and nothing keeps it awake.
  const int islands = static_cast<int>(memberStart_.size()) - 1;
  std::vector<char> touches(islands, 0);
  for (const Contact& c : scene.contacts) touches[island_[c.particle[0]]] = 1;
  if (held_.size() != x.size()) held_ = x;
  for (int i = 0; i < islands; ++i) {
    bool sleeps = touches[i];
    for (int k = memberStart_[i]; sleeps && k < memberStart_[i + 1]; ++k) {
      const int p = members_[k];
      sleeps = !keptAwake_[p] && (scene.inverseMass[p] == 0.0 || rested_[p] >= settings.sleepTime);
    }
    if (!sleeps) continue;
    for (int k = memberStart_[i]; k < memberStart_[i + 1]; ++k) {
      const int p = members_[k];
      if (scene.inverseMass[p] == 0.0 || asleep_[p]) continue;
      asleep_[p] = 1;
      group_[p] = members_[memberStart_[i]];
      held_.segment<2>(2 * p) = x.segment<2>(2 * p);
      ++sleeping_;
    }
  }
}

}  // namespace particles
