// Contacts and constraints of an island resolved together (coupled_contacts.h).
#include "coupled_contacts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_track.h"

namespace particles {

namespace {

enum class RowKind { Bilateral, Normal, Friction };

// One block of a row's J: the particle and ∂C/∂x_particle.
struct Block {
  int particle;
  Eigen::Vector2d J;
};

struct Row {
  RowKind kind;
  int first = 0, count = 0;  // blocks [first, first + count)
  double invK = 0.0;         // 1 / (Σ w |J|²); 0 for a row of pinned particles
  double norm = 0.0;         // |J| over all blocks
  double target = 0.0;       // velocity target (J v = target, or ≥ for a normal)
  double lambda = 0.0;       // accumulated impulse
  double mu = 0.0;           // friction rows: Coulomb's coefficient
  int normal = -1;           // friction rows: their normal row
  int constraint = -1;       // bilateral rows: the constraint's index
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  // contact rows: a point of the plane
  std::int64_t key = 0;      // warm-start key
};

constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::int64_t contactKey(int particle, int collider, int colliders, bool friction) {
  return (static_cast<std::int64_t>(particle) * colliders + collider) * 2 + (friction ? 1 : 0);
}

}  // namespace

bool touchesCollider(const std::vector<Collider>& colliders, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                     double r, double slop) {
  for (const Collider& c : colliders)
    if (c.sweep(a, b, r, slop) || c.distance(b).distance - r <= slop) return true;
  return false;
}

void CoupledContacts::buildAdjacency(const ConstraintList& constraints, int particles) {
  first_.assign(particles + 1, 0);
  for (const auto& c : constraints)
    for (int p : c->particles()) ++first_[p + 1];
  for (int p = 0; p < particles; ++p) first_[p + 1] += first_[p];
  ids_.assign(first_[particles], 0);
  std::vector<int> fill(first_.begin(), first_.end() - 1);
  for (int k = 0; k < static_cast<int>(constraints.size()); ++k)
    for (int p : constraints[k]->particles()) ids_[fill[p]++] = k;
}

const std::vector<int>& CoupledContacts::island(const ConstraintList& constraints, int particles,
                                                std::uint64_t structure, const std::vector<int>& touching) {
  if (structure != structure_ || static_cast<int>(first_.size()) != particles + 1) {
    buildAdjacency(constraints, particles);
    structure_ = structure;
    previous_.clear();
  }
  inIsland_.assign(particles, 0);
  island_.clear();
  queue_.clear();
  for (int i : touching)
    if (constrained(i) && !inIsland_[i]) {
      inIsland_[i] = 1;
      queue_.push_back(i);
    }
  // Breadth-first through the constraints: every particle joined to a
  // touching one by any chain of constraints is in its island.
  for (std::size_t head = 0; head < queue_.size(); ++head) {
    const int p = queue_[head];
    island_.push_back(p);
    for (int k = first_[p]; k < first_[p + 1]; ++k)
      for (int q : constraints[ids_[k]]->particles())
        if (!inIsland_[q]) {
          inIsland_[q] = 1;
          queue_.push_back(q);
        }
  }
  std::sort(island_.begin(), island_.end());
  return island_;
}

// The rows of one island's solve and the phases that relax them (coupled_contacts.h,
// steps 1–4), kept between steps so that their arrays are not allocated again.
struct CoupledContacts::Rows {
  const ConstraintList* constraints = nullptr;
  const Eigen::VectorXd* mass = nullptr;
  const Eigen::VectorXd* inverseMass = nullptr;
  std::vector<Row> rows;
  std::vector<Block> blocks;
  std::vector<Eigen::Vector2d> jScratch, jdotScratch;
  std::vector<Eigen::Vector2d> startJ;  // DriftCorrection::Shake: each block's J at the step's start
  std::vector<int> islandConstraints;
  DriftCorrection drift = DriftCorrection::AtEnd;
  double dt = 0.0;

  void begin(const ConstraintList& c, const Eigen::VectorXd& m, const Eigen::VectorXd& w, DriftCorrection d,
             double h) {
    constraints = &c;
    mass = &m;
    inverseMass = &w;
    drift = d;
    dt = h;
    rows.clear();
    blocks.clear();
    startJ.clear();
  }
  double evaluateConstraint(int c, const Eigen::VectorXd& x, const Eigen::VectorXd& v, Row& row);
  void addConstraintRows(const StepStart& start, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  bool correctConstraint(Row& row, Eigen::VectorXd& x, Eigen::VectorXd& v, double& error);
  void addContactRows(int i, int k, int colliders, const Collider& collider, const Eigen::Vector2d& normal,
                      const Eigen::Vector2d& point, double target);
  void correctPositions(const ContactSettings& settings, Eigen::VectorXd& x, Eigen::VectorXd& v);
  double velocityOf(const Row& row, const Eigen::VectorXd& v) const;
  void applyImpulse(const Row& row, double impulse, Eigen::VectorXd& v) const;
  void warmStart(const std::unordered_map<std::int64_t, double>& previous, Eigen::VectorXd& v);
  void solveVelocities(const ContactSettings& settings, Eigen::VectorXd& v, CoupledSolveStats& stats);
};

CoupledContacts::CoupledContacts() : rows_(std::make_unique<Rows>()) {}
CoupledContacts::~CoupledContacts() = default;
CoupledContacts::CoupledContacts(CoupledContacts&&) noexcept = default;
CoupledContacts& CoupledContacts::operator=(CoupledContacts&&) noexcept = default;

// Fills a row's blocks from its constraint's J at x; returns C.
double CoupledContacts::Rows::evaluateConstraint(int c, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                                 Row& row) {
  const Constraint& constraint = *(*constraints)[c];
  const std::vector<int>& ps = constraint.particles();
  jScratch.assign(ps.size(), Eigen::Vector2d::Zero());
  jdotScratch.assign(ps.size(), Eigen::Vector2d::Zero());
  ConstraintRow out{0.0, 0.0, jScratch.data(), jdotScratch.data()};
  constraint.evaluate(Phase{x, v, *mass, *inverseMass}, out);
  double k = 0.0, norm2 = 0.0;
  for (std::size_t b = 0; b < ps.size(); ++b) {
    blocks[row.first + b] = {ps[b], jScratch[b]};
    k += (*inverseMass)[ps[b]] * jScratch[b].squaredNorm();
    norm2 += jScratch[b].squaredNorm();
  }
  row.invK = k > 0.0 ? 1.0 / k : 0.0;
  row.norm = std::sqrt(norm2);
  return out.C;
}

// 1. The island's constraints as bilateral rows, each once (with their J at
// the step's start for DriftCorrection::Shake).
void CoupledContacts::Rows::addConstraintRows(const StepStart& start, const Eigen::VectorXd& x,
                                              const Eigen::VectorXd& v) {
  for (int c : islandConstraints) {
    Row row{RowKind::Bilateral};
    row.first = static_cast<int>(blocks.size());
    row.count = static_cast<int>((*constraints)[c]->particles().size());
    row.constraint = c;
    row.key = -1 - static_cast<std::int64_t>(c);
    blocks.resize(blocks.size() + row.count);
    if (drift == DriftCorrection::Shake) {
      evaluateConstraint(c, start.x, start.v, row);
      startJ.resize(blocks.size());
      for (int b = row.first; b < row.first + row.count; ++b) startJ[b] = blocks[b].J;
    }
    evaluateConstraint(c, x, v, row);
    rows.push_back(row);
  }
}

// One Newton step of a bilateral row towards C = 0: along W J at the end, or
// (Shake) along W J₀ at the start, −C / (J · W J₀) of it, the move carried
// into the velocity. A start gradient nearly normal to the present one (the
// constraint turned by more than about 75° in the step) falls back to the
// present one. Returns false for a row that cannot move; `error` is |C| / |J|.
bool CoupledContacts::Rows::correctConstraint(Row& row, Eigen::VectorXd& x, Eigen::VectorXd& v, double& error) {
  const Eigen::VectorXd& w = *inverseMass;
  const double C = evaluateConstraint(row.constraint, x, v, row);
  if (row.invK == 0.0 || row.norm == 0.0) return false;
  error = std::abs(C) / row.norm;
  const bool shake = drift == DriftCorrection::Shake;
  double along = 0.0, sizes = 0.0;  // J · W J₀ and Σ w |J| |J₀|
  if (shake)
    for (int b = row.first; b < row.first + row.count; ++b) {
      const double wp = w[blocks[b].particle];
      along += wp * blocks[b].J.dot(startJ[b]);
      sizes += wp * blocks[b].J.norm() * startJ[b].norm();
    }
  const bool useStart = shake && along > 0.25 * sizes;
  const double scale = useStart ? -C / along : -C * row.invK;
  for (int b = row.first; b < row.first + row.count; ++b) {
    const int p = blocks[b].particle;
    const Eigen::Vector2d move = (w[p] * scale) * (useStart ? startJ[b] : blocks[b].J);
    x.segment<2>(2 * p) += move;
    if (shake) v.segment<2>(2 * p) += move / dt;
  }
  return true;
}

// 1. A contact of particle i with collider k: a normal row on the plane of
// the face (normal, point) with its velocity target, and a friction row along it.
void CoupledContacts::Rows::addContactRows(int i, int k, int colliders, const Collider& collider,
                                           const Eigen::Vector2d& normal, const Eigen::Vector2d& point,
                                           double target) {
  const double w = (*inverseMass)[i];
  Row normalRow{RowKind::Normal};
  normalRow.first = static_cast<int>(blocks.size());
  normalRow.count = 1;
  normalRow.invK = 1.0 / w;
  normalRow.norm = 1.0;
  normalRow.target = target;
  normalRow.point = point;
  normalRow.key = contactKey(i, k, colliders, false);
  blocks.push_back({i, normal});
  rows.push_back(normalRow);
  if (collider.friction <= 0.0) return;
  Row friction{RowKind::Friction};
  friction.first = static_cast<int>(blocks.size());
  friction.count = 1;
  friction.invK = 1.0 / w;
  friction.norm = 1.0;
  friction.mu = collider.friction;
  friction.normal = static_cast<int>(rows.size()) - 1;
  friction.key = contactKey(i, k, colliders, true);
  blocks.push_back({i, Eigen::Vector2d(-normal.y(), normal.x())});
  rows.push_back(friction);
}

// 3. Nonlinear Gauss–Seidel over the rows' position errors (friction rows have none).
void CoupledContacts::Rows::correctPositions(const ContactSettings& settings, Eigen::VectorXd& x,
                                             Eigen::VectorXd& v) {
  const Eigen::VectorXd& w = *inverseMass;
  for (int pass = 0; pass < settings.positionIterations; ++pass) {
    double worst = 0.0;
    for (Row& row : rows) {
      if (row.kind == RowKind::Friction) continue;
      double error = 0.0;  // C / |J|: a length
      if (row.kind == RowKind::Bilateral) {
        if (!correctConstraint(row, x, v, error)) continue;
      } else {
        const Eigen::Vector2d& n = blocks[row.first].J;
        const int p = blocks[row.first].particle;
        const double C = n.dot(x.segment<2>(2 * p) - row.point);
        if (C >= 0.0) continue;
        error = -C;
        x.segment<2>(2 * p) += (w[p] * (-C * row.invK)) * n;
      }
      worst = std::max(worst, error);
    }
    if (!(worst > settings.slop)) break;
  }
}

double CoupledContacts::Rows::velocityOf(const Row& row, const Eigen::VectorXd& v) const {
  double jv = 0.0;
  for (int b = row.first; b < row.first + row.count; ++b) jv += blocks[b].J.dot(v.segment<2>(2 * blocks[b].particle));
  return jv;
}

void CoupledContacts::Rows::applyImpulse(const Row& row, double impulse, Eigen::VectorXd& v) const {
  const Eigen::VectorXd& w = *inverseMass;
  for (int b = row.first; b < row.first + row.count; ++b) {
    const int p = blocks[b].particle;
    v.segment<2>(2 * p) += (w[p] * impulse) * blocks[b].J;
  }
}

// Warm start: the same rows' impulses of the last step (a bounce starts cold).
void CoupledContacts::Rows::warmStart(const std::unordered_map<std::int64_t, double>& previous, Eigen::VectorXd& v) {
  for (Row& row : rows) {
    if (row.invK == 0.0 || (row.kind == RowKind::Normal && row.target > 0.0)) continue;
    const auto found = previous.find(row.key);
    if (found == previous.end()) continue;
    double lambda = found->second;
    if (row.kind == RowKind::Normal) lambda = std::max(0.0, lambda);
    if (row.kind == RowKind::Friction) {
      const double bound = row.mu * rows[row.normal].lambda;
      lambda = std::clamp(lambda, -bound, bound);
    }
    row.lambda = lambda;
    applyImpulse(row, lambda, v);
  }
}

// 4. Projected Gauss–Seidel: constraints, friction, normals in each sweep.
void CoupledContacts::Rows::solveVelocities(const ContactSettings& settings, Eigen::VectorXd& v,
                                            CoupledSolveStats& stats) {
  const RowKind order[] = {RowKind::Bilateral, RowKind::Friction, RowKind::Normal};
  for (int sweep = 0; sweep < settings.coupledIterations; ++sweep) {
    double largest = 0.0;
    for (RowKind kind : order)
      for (Row& row : rows) {
        if (row.kind != kind || row.invK == 0.0) continue;
        double lo = -kInfinity, hi = kInfinity;
        if (kind == RowKind::Normal) lo = 0.0;
        if (kind == RowKind::Friction) hi = row.mu * rows[row.normal].lambda, lo = -hi;
        const double next = std::clamp(row.lambda + (row.target - velocityOf(row, v)) * row.invK, lo, hi);
        const double impulse = next - row.lambda;
        if (impulse == 0.0) continue;
        row.lambda = next;
        applyImpulse(row, impulse, v);
        largest = std::max(largest, std::abs(impulse) / (row.invK * row.norm));
      }
    stats.iterations = sweep + 1;
    stats.residual = largest;
    if (!(largest > settings.coupledTolerance)) break;
  }
}

// The island's constraints: each once, from its lowest particle in the island.
void CoupledContacts::collectIslandConstraints(const ConstraintList& constraints) {
  std::vector<int>& out = rows_->islandConstraints;
  out.clear();
  for (int p : island_)
    for (int k = first_[p]; k < first_[p + 1]; ++k) {
      const int c = ids_[k];
      const std::vector<int>& ps = constraints[c]->particles();
      if (*std::min_element(ps.begin(), ps.end()) == p) out.push_back(c);
    }
}

// 1–2. Each island particle's contacts: the face its path entered or its end
// touches, with the bounce of a contact new this step from the impact speed.
int CoupledContacts::addContacts(const std::vector<Collider>& colliders, const StepStart& start,
                                 const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                                 const ContactSettings& settings, const Eigen::VectorXd& x,
                                 const Eigen::VectorXd& v) {
  const int nColliders = static_cast<int>(colliders.size());
  const contact::ColliderBoxes boxes(colliders);
  int contacts = 0;
  for (int i : island_) {
    if (inverseMass[i] == 0.0) continue;
    const double r = radius[i];
    const Eigen::Vector2d x0 = start.x.segment<2>(2 * i), v0 = start.v.segment<2>(2 * i);
    const Eigen::Vector2d x1 = x.segment<2>(2 * i), v1 = v.segment<2>(2 * i);
    if (!boxes.near(colliders, x0, x1, r + settings.slop)) continue;
    for (int k = 0; k < nColliders; ++k) {
      const Collider& collider = colliders[k];
      Eigen::Vector2d normal, point;
      if (const std::optional<double> s = collider.sweep(x0, x1, r, settings.slop)) {
        point = contact::ontoSurface(collider, x0 + *s * (x1 - x0), r, &normal);
      } else if (collider.distance(x1).distance - r <= settings.slop) {
        point = contact::ontoSurface(collider, x1, r, &normal);
      } else {
        continue;
      }
      const double vn = normal.dot(v1);
      double target = 0.0;
      if (vn < 0.0 && previous_.find(contactKey(i, k, nColliders, false)) == previous_.end()) {
        const double depth = std::max(0.0, -normal.dot(x1 - point));
        const double an = normal.dot(v1 - v0) / start.dt;
        const double impact = std::sqrt(std::max(0.0, vn * vn + 2.0 * an * depth));
        if (collider.restitution * impact > settings.restitutionThreshold) target = collider.restitution * impact;
      }
      rows_->addContactRows(i, k, nColliders, collider, normal, point, target);
      ++contacts;
    }
  }
  return contacts;
}

CoupledSolveStats CoupledContacts::solve(const ConstraintList& constraints, const std::vector<Collider>& colliders,
                                         const StepStart& start, const Eigen::VectorXd& mass,
                                         const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                                         const ContactSettings& settings, DriftCorrection drift, Eigen::VectorXd& x,
                                         Eigen::VectorXd& v) {
  CoupledSolveStats stats;
  if (island_.empty()) {
    previous_.clear();
    return stats;
  }
  Rows& R = *rows_;
  R.begin(constraints, mass, inverseMass, drift, start.dt);
  collectIslandConstraints(constraints);
  R.addConstraintRows(start, x, v);
  // The constraints' own drift first: a contact is judged where the
  // constraints put the particle (a bead that the integrator let drift off
  // its wire into a floor tangent to the wire does not touch that floor).
  R.correctPositions(settings, x, v);
  stats.contacts = addContacts(colliders, start, inverseMass, radius, settings, x, v);
  stats.rows = static_cast<int>(R.rows.size());
  // 3. Position drift of both kinds of rows, corrected together, before the
  // velocities: the velocity rows are then those of the final positions, so
  // the velocities leave the step consistent with the constraints where they
  // are (a correction made after would turn a rod by depth/length and leave
  // J v ≠ 0 there, a drift the next step carries on).
  R.correctPositions(settings, x, v);
  for (Row& row : R.rows)
    if (row.kind == RowKind::Bilateral) R.evaluateConstraint(row.constraint, x, v, row);
  R.warmStart(previous_, v);
  R.solveVelocities(settings, v, stats);
  previous_.clear();
  for (const Row& row : R.rows) previous_[row.key] = row.lambda;
  return stats;
}

}  // namespace particles
