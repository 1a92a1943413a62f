// Contacts and the constraints that hold their particles, solved together
// (contact_solver.h): the rows, their islands, the choice of method per
// island and the warm start.
#include "contact_solver.h"

#include <algorithm>
#include <deque>
#include <cmath>
#include <limits>
#include <numeric>

#include "solver_rows.h"

namespace particles {

using solve::Row;
using solve::RowKind;

namespace {

// The multipliers a contact's rows ended the last solve with.
struct Kept {
  std::uint64_t key;
  double lambdaN, lambdaT;
  double side;  // Contact::side
};

// The target of a normal row that holds nothing: any approach is allowed
// (its impulse stays 0; the row keeps the contact's warm start).
constexpr double kOpen = -std::numeric_limits<double>::infinity();

int findRoot(std::vector<int>& parent, int a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

}  // namespace

struct ContactSolver::Rows {
  solve::RowSystem system;
  std::vector<int> constraintsInIsland;
  // Constraint adjacency (rebuilt when the structure changes).
  std::uint64_t structure = 0;
  std::vector<int> first, ids;  // particle p's constraints: ids[first[p] .. first[p + 1])
  std::vector<char> inIsland;
  std::vector<int> queue;
  // Islands of rows: union–find over the particles the rows move; each
  // island's contact rows and its constraints as one block.
  std::vector<int> parent, islandOf;
  std::vector<std::vector<int>> contactRows;
  std::deque<solve::DirectBlock> blocks;  // not moved as it grows (the LU cannot be)
  // Warm start: the last solve's contact impulses sorted by key, and the
  // constraints' (indexed by constraint, valid while the structure holds).
  std::vector<Kept> kept, keeping;
  std::vector<double> keptLambda;
  std::vector<char> keptValid;

  void buildAdjacency(const ConstraintList& constraints, int particles);
  void findParticles(const ContactSolveInput& in, const std::vector<Contact>& contacts, int particles,
                     std::vector<int>& island);
  void addRows(const ContactSolveInput& in, const Eigen::VectorXd& x);
  int findIslands(int particles);
  void prepareSolve(const ContactSolveInput& in, const ContactSettings& settings);
  void warmStart(Eigen::VectorXd& v);
  void prepareRelax(const ContactSettings& settings, const Eigen::VectorXd& x);
  void keep(int constraintCount);
  const Kept* keptFor(std::uint64_t key) const;
};

ContactSolver::ContactSolver() : rows_(std::make_unique<Rows>()) {}
ContactSolver::~ContactSolver() = default;
ContactSolver::ContactSolver(ContactSolver&&) noexcept = default;
ContactSolver& ContactSolver::operator=(ContactSolver&&) noexcept = default;

void ContactSolver::resetWarmStart() {
  rows_->kept.clear();
  rows_->keptValid.clear();
}

bool ContactSolver::persists(std::uint64_t key) const { return rows_->keptFor(key) != nullptr; }

double ContactSolver::lastSide(std::uint64_t key) const {
  const Kept* k = rows_->keptFor(key);
  return k ? k->side : 0.0;
}

const Kept* ContactSolver::Rows::keptFor(std::uint64_t key) const {
  const auto found = std::lower_bound(kept.begin(), kept.end(), key,
                                      [](const Kept& k, std::uint64_t value) { return k.key < value; });
  return found != kept.end() && found->key == key ? &*found : nullptr;
}

void ContactSolver::Rows::buildAdjacency(const ConstraintList& constraints, int particles) {
  first.assign(particles + 1, 0);
  for (const auto& c : constraints)
    for (int p : c->particles()) ++first[p + 1];
  for (int p = 0; p < particles; ++p) first[p + 1] += first[p];
  ids.assign(first[particles], 0);
  std::vector<int> fill(first.begin(), first.end() - 1);
  for (int k = 0; k < static_cast<int>(constraints.size()); ++k)
    for (int p : constraints[k]->particles()) ids[fill[p]++] = k;
}

// The contacts' particles and every particle joined to them by a chain of
// constraints through particles that move (a pinned particle joins nothing:
// chains hung from one pin are not one island), ascending; the constraints
// among them, each once.
void ContactSolver::Rows::findParticles(const ContactSolveInput& in, const std::vector<Contact>& contacts,
                                        int particles, std::vector<int>& island) {
  const Eigen::VectorXd& w = in.inverseMass;
  inIsland.assign(particles, 0);
  queue.clear();
  for (const Contact& c : contacts)
    for (int k = 0; k < c.count(); ++k) {
      const int p = c.particle[k];
      if (w[p] > 0.0 && !inIsland[p]) inIsland[p] = 1, queue.push_back(p);
    }
  constraintsInIsland.clear();
  if (in.withConstraints)
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const int p = queue[head];
      for (int k = first[p]; k < first[p + 1]; ++k)
        for (int q : in.constraints[ids[k]]->particles())
          if (!inIsland[q] && w[q] > 0.0) inIsland[q] = 1, queue.push_back(q);
    }
  island = queue;
  std::sort(island.begin(), island.end());
  if (!in.withConstraints) return;
  for (int p : island)
    for (int k = first[p]; k < first[p + 1]; ++k) {
      int lowest = particles;
      for (int q : in.constraints[ids[k]]->particles())
        if (inIsland[q]) lowest = std::min(lowest, q);
      if (lowest == p) constraintsInIsland.push_back(ids[k]);
    }
}

// The rows: each constraint of the island (bilateral, its J at the
// references), each contact's normal and, with μ > 0, its friction right
// after it (from the contact as the narrow phase found it).
void ContactSolver::Rows::addRows(const ContactSolveInput& in, const Eigen::VectorXd&) {
  solve::RowSystem& R = system;
  for (int c : constraintsInIsland) {
    Row row{RowKind::Bilateral};
    row.first = static_cast<int>(R.blocks.size());
    row.count = static_cast<int>(in.constraints[c]->particles().size());
    row.source = c;
    R.blocks.resize(R.blocks.size() + row.count);
    R.evaluateConstraint(row, in.refs.x);
    R.rows.push_back(row);
  }
  for (int k = 0; k < static_cast<int>(R.contacts->size()); ++k) {
    const Contact& c = (*R.contacts)[k];
    Row normal{RowKind::Normal};
    normal.first = static_cast<int>(R.blocks.size());
    normal.count = c.count();
    normal.source = k;
    R.blocks.resize(R.blocks.size() + normal.count);
    R.rows.push_back(normal);
    const int normalRow = static_cast<int>(R.rows.size()) - 1;
    if (c.friction > 0.0) {
      Row friction{RowKind::Friction};
      friction.first = static_cast<int>(R.blocks.size());
      friction.count = c.count();
      friction.source = k;
      friction.normal = normalRow;
      R.blocks.resize(R.blocks.size() + friction.count);
      R.rows[normalRow].friction = normalRow + 1;
      R.rows.push_back(friction);
    }
    R.setContactBlocks(normalRow);
  }
}

// Rows that move a common particle are in one island: its contact rows
// (ascending, a friction row right after its normal) and its constraints as
// one block. Returns the number of islands.
int ContactSolver::Rows::findIslands(int particles) {
  const solve::RowSystem& R = system;
  parent.resize(particles);
  std::iota(parent.begin(), parent.end(), 0);
  const Eigen::VectorXd& w = R.in->inverseMass;
  for (const Row& row : R.rows) {
    int root = -1;
    for (int b = row.first; b < row.first + row.count; ++b) {
      const int p = R.blocks[b].particle;
      if (w[p] == 0.0) continue;
      const int r = findRoot(parent, p);
      if (root < 0) root = r;
      else if (r != root) parent[r] = root;
    }
  }
  const int rowCount = static_cast<int>(R.rows.size());
  islandOf.assign(rowCount, -1);
  std::vector<int> label(particles, -1);
  int islands = 0;
  for (int r = 0; r < rowCount; ++r) {
    const Row& row = R.rows[r];
    for (int b = row.first; b < row.first + row.count; ++b) {
      const int p = R.blocks[b].particle;
      if (w[p] == 0.0) continue;
      const int root = findRoot(parent, p);
      if (label[root] < 0) label[root] = islands++;
      islandOf[r] = label[root];
      break;
    }
  }
  if (static_cast<int>(contactRows.size()) < islands) contactRows.resize(islands);
  if (static_cast<int>(blocks.size()) < islands) blocks.resize(islands);
  std::vector<std::vector<int>> bilateral(islands);
  for (int i = 0; i < islands; ++i) contactRows[i].clear();
  for (int r = 0; r < rowCount; ++r) {
    if (islandOf[r] < 0) continue;  // a row of pinned particles moves nothing
    (R.rows[r].kind == RowKind::Bilateral ? bilateral[islandOf[r]] : contactRows[islandOf[r]]).push_back(r);
  }
  for (int i = 0; i < islands; ++i) blocks[i].reset(std::move(bilateral[i]));
  return islands;
}

// Stage 1's targets: a contact may close its gap at the references over the
// time h left, no more; a constraint's rows hold (J v = 0).
void ContactSolver::Rows::prepareSolve(const ContactSolveInput& in, const ContactSettings& settings) {
  solve::RowSystem& R = system;
  for (Row& row : R.rows) {
    row.lambda = 0.0;
    row.target = 0.0;
    row.h = 0.0;
    for (int b = row.first; b < row.first + row.count; ++b) {
      const double h = in.refs.h[R.blocks[b].particle];
      if (in.inverseMass[R.blocks[b].particle] > 0.0 && (row.h == 0.0 || h < row.h)) row.h = h;
    }
    if (row.kind != RowKind::Normal) continue;
    // A contact the path entered stops at its surface; one that was only
    // near holds only if it touched at the references (a bead on a wire
    // passing over a floor tangent to the wire, near it but never in it, is
    // not held back by a linear guess at its path).
    const Contact& c = (*R.contacts)[row.source];
    const double gap = c.linearGap(in.refs.x);
    // An overlap is pushed out by the projection (stage 3), in positions
    // only: a velocity that closes no gap here would stay as speed.
    row.target = row.h > 0.0 && (c.swept || gap <= settings.slop) ? -std::max(gap, 0.0) / row.h : kOpen;
  }
}

// The same rows' impulses of the last step.
void ContactSolver::Rows::warmStart(Eigen::VectorXd& v) {
  solve::RowSystem& R = system;
  for (Row& row : R.rows) {
    if (row.invK == 0.0) continue;
    double lambda = 0.0;
    if (row.kind == RowKind::Bilateral) {
      if (row.source >= static_cast<int>(keptValid.size()) || !keptValid[row.source]) continue;
      lambda = keptLambda[row.source];
    } else {
      const Kept* k = keptFor((*R.contacts)[row.source].key);
      if (!k) continue;
      lambda = row.kind == RowKind::Normal ? std::max(0.0, k->lambdaN) : k->lambdaT;
      if (row.kind == RowKind::Friction) {
        const double bound = R.frictionBound(row);
        lambda = std::clamp(lambda, -bound, bound);
      }
    }
    row.lambda = lambda;
    R.move(row, lambda, v);
  }
}

// Stage 4's rows at the final positions, their impulses kept: each contact's
// normal where the particles now are, and its target: a bounce for a new
// contact that struck; one left open holds nothing.
void ContactSolver::Rows::prepareRelax(const ContactSettings& settings, const Eigen::VectorXd& x) {
  solve::RowSystem& R = system;
  for (std::size_t r = 0; r < R.rows.size(); ++r) {
    Row& row = R.rows[r];
    if (row.kind == RowKind::Bilateral) {
      R.evaluateConstraint(row, x);
    } else if (row.kind == RowKind::Normal) {
      // The contact's normal of the solve is kept (as Box2D keeps a
      // contact's normal through its substeps and relax): the impulses of
      // stage 1 continue along the rows they were applied along.
      // A row left open holds nothing, unless it pushed in the solve: then it
      // may let go only as far as its gap closes over a step (a row left a
      // hair open by an unconverged solve does not hand back the speed it
      // took, so a position moved by a velocity keeps that velocity).
      const double gap = (*R.contacts)[row.source].linearGap(x);
      if (gap <= settings.slop) row.target = (*R.contacts)[row.source].bounce;
      else row.target = row.lambda > 0.0 && row.h > 0.0 ? -gap / row.h : kOpen;
    }
  }
}

// This solve's multipliers, kept for the next one.
void ContactSolver::Rows::keep(int constraintCount) {
  const solve::RowSystem& R = system;
  keeping.clear();
  keptLambda.assign(constraintCount, 0.0);
  keptValid.assign(constraintCount, 0);
  for (const Row& row : R.rows) {
    if (row.kind == RowKind::Bilateral) {
      keptLambda[row.source] = row.lambda;
      keptValid[row.source] = 1;
    } else if (row.kind == RowKind::Normal) {
      const Contact& contact = (*R.contacts)[row.source];
      Kept k{contact.key, row.lambda, 0.0, contact.side};
      if (row.friction >= 0) k.lambdaT = R.rows[row.friction].lambda;
      keeping.push_back(k);
    }
  }
  std::sort(keeping.begin(), keeping.end(), [](const Kept& a, const Kept& b) { return a.key < b.key; });
  kept.swap(keeping);
}

// An island's velocities: an island with constraints and not too many
// contact rows by relaxation on the Schur complement of its constraints
// (reduced.cpp), any other (a pile, contacts alone) by block relaxation from
// its warm start (relax.cpp).
void ContactSolver::solveIsland(Rows& S, int island, const ContactSettings& settings, Eigen::VectorXd& v,
                                ContactSolveStats& stats) {
  solve::RowSystem& R = S.system;
  solve::Relaxed done;
  const bool reduced = !S.blocks[island].empty() && static_cast<int>(S.contactRows[island].size()) <= solve::kReducedRows;
  if (reduced) done = solve::relaxReduced(R, S.contactRows[island], S.blocks[island], settings, v);
  else done = solve::relaxVelocities(R, S.contactRows[island], S.blocks[island], settings, v);
  stats.iterations = std::max(stats.iterations, done.passes);
  stats.residual = std::max(stats.residual, done.largest);
}

ContactSolveStats ContactSolver::solve(std::vector<Contact>& contacts, const ContactSolveInput& in,
                                       std::uint64_t structure, const ContactSettings& settings, Eigen::VectorXd& x,
                                       Eigen::VectorXd& v) {
  ContactSolveStats stats;
  Rows& S = *rows_;
  solve::RowSystem& R = S.system;
  const int particles = static_cast<int>(in.mass.size());
  if (structure != S.structure || static_cast<int>(S.first.size()) != particles + 1) {
    S.buildAdjacency(in.constraints, particles);
    S.structure = structure;
    resetWarmStart();
  }
  R.in = &in;
  R.contacts = &contacts;
  R.rows.clear();
  R.blocks.clear();
  island_.clear();
  if (contacts.empty()) {
    resetWarmStart();
    return stats;
  }
  S.findParticles(in, contacts, particles, island_);
  S.addRows(in, x);
  const int islands = S.findIslands(particles);
  stats.rows = static_cast<int>(R.rows.size());
  // 0. The references and the ends on the constraints; a contact the path
  // entered only by drifting off them is not entered.
  for (int i = 0; i < islands; ++i) {
    if (S.blocks[i].empty()) continue;
    for (Eigen::VectorXd* state : {&x, &in.refs.x})
      for (int pass = 0; pass < settings.positionIterations; ++pass)
        if (!(S.blocks[i].projectPositions(R, *state) > settings.slop)) break;
    for (const int r : S.contactRows[i]) {
      Contact& c = contacts[R.rows[r].source];
      if (R.rows[r].kind == RowKind::Normal && c.swept && c.linearGap(x) > settings.slop) c.swept = false;
    }
  }
  // 1. Solve the velocities, before any position moves.
  S.prepareSolve(in, settings);
  S.warmStart(v);
  for (int i = 0; i < islands; ++i) solveIsland(S, i, settings, v, stats);
  // 2. Integrate the positions the rows hold from their references.
  for (const int p : island_) x.segment<2>(2 * p) = in.refs.x.segment<2>(2 * p) + in.refs.h[p] * v.segment<2>(2 * p);
  // 3. Project: the constraints' drift, the overlap left.
  for (int i = 0; i < islands; ++i) {
    const solve::Relaxed done = solve::projectPositions(R, S.contactRows[i], S.blocks[i], settings, x);
    stats.positionPasses = std::max(stats.positionPasses, done.passes);
  }
  // 4. Relax the velocities at the final positions.
  S.prepareRelax(settings, x);
  stats.iterations = 0;
  stats.residual = 0.0;
  for (int i = 0; i < islands; ++i) solveIsland(S, i, settings, v, stats);
  S.keep(static_cast<int>(in.constraints.size()));
  return stats;
}

}  // namespace particles
