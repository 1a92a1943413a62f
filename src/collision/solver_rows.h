#pragma once
// The rows of the contact solve (contact_solver.h) and what its stages do
// with a row: evaluate it where the particles are, move them along W Jᵀ, read
// J v. The constraints of an island are solved as one block (DirectBlock);
// the contact rows are relaxed one by one (relax.cpp), or on the Schur
// complement of the island's constraints (reduced.cpp).
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "contact.h"
#include "contact_solver.h"

namespace particles::solve {

enum class RowKind : std::uint8_t { Bilateral, Friction, Normal };

// One block of a row's J: the particle and ∂C/∂x_particle.
struct Block {
  int particle;
  Eigen::Vector2d J;
};

struct Row {
  RowKind kind;
  int first = 0, count = 0;  // blocks [first, first + count)
  double invK = 0.0;         // 1 / (Σ w |J|²); 0 for a row of pinned particles
  double norm = 1.0;         // |J| over all blocks
  double target = 0.0;       // velocity target (J v = target, or ≥ for a normal)
  double lambda = 0.0;       // accumulated impulse
  double mu = 0.0;           // normal rows: the projection's accumulated push
  double h = 0.0;            // time from the particles' references to the step's end (the least of them)
  int source = -1;           // bilateral: the constraint; contact rows: the contact
  int normal = -1;           // friction rows: their normal row
  int friction = -1;         // normal rows: their friction row, if any
};

// The rows of one solve and the state they act on.
struct RowSystem {
  const ContactSolveInput* in = nullptr;
  std::vector<Contact>* contacts = nullptr;
  std::vector<Row> rows;
  std::vector<Block> blocks;
  std::vector<Eigen::Vector2d> jScratch, jdotScratch;

  // A bilateral row's blocks from its constraint's J at x; returns C.
  double evaluateConstraint(Row& row, const Eigen::VectorXd& x);
  // A contact's normal row (and its friction row) from the contact evaluated
  // where the particles are at x; returns the gap.
  double evaluateContact(int normalRow, const Eigen::VectorXd& x);
  // The same rows' blocks from the contact's present normal and weights.
  void setContactBlocks(int normalRow);
  // Moves x (or v) along W Jᵀ by `amount`.
  void move(const Row& row, double amount, Eigen::VectorXd& x) const;
  double velocityOf(const Row& row, const Eigen::VectorXd& v) const;
  // Friction's bound: μ times its normal row's impulse.
  double frictionBound(const Row& row) const;
};

// Rows solved together directly: K = J W Jᵀ over the block's rows, assembled
// from the blocks that share a particle and factorised (sparse LU; a diagonal regularisation of 1e-10 of
// its largest entry keeps redundant rows — a closed loop of rods, a contact
// that a rod already holds — solvable). An island's constraints are one such
// block; the active-set solve makes one of its active rows.
class DirectBlock {
 public:
  void reset(std::vector<int> rows) { rows_ = std::move(rows); }
  void assign(const std::vector<int>& rows) { rows_ = rows; }
  bool empty() const { return rows_.empty(); }
  const std::vector<int>& rows() const { return rows_; }
  // Factorises J W Jᵀ of the rows' present blocks (for solveVelocities).
  bool factorVelocities(const RowSystem& R);
  // λ += δ, v += W Jᵀ δ with K δ = target − J v: the block's rows hold
  // exactly. Returns the largest |target − J v| / |J| it corrected.
  double solveVelocities(RowSystem& R, Eigen::VectorXd& v);
  // One Newton step towards C(x) = 0: the rows evaluated at x, K = J W Jᵀ,
  // x += W Jᵀ δ with K δ = −C (the velocities are the relax's). Returns the
  // largest |C| / |J| before the step.
  double projectPositions(RowSystem& R, Eigen::VectorXd& x);
  // K⁻¹ B for the last factorisation (B's rows in the order of rows()).
  Eigen::MatrixXd solveColumns(const Eigen::MatrixXd& B) const { return lu_.solve(B); }

 private:
  bool factor(const RowSystem& R);
  std::vector<int> rows_;
  std::vector<std::array<int, 3>> entries_;  // (particle, place in rows_, block)
  std::vector<Eigen::Triplet<double>> triplets_;
  Eigen::SparseMatrix<double> K_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  Eigen::VectorXd rhs_, delta_;
};

// Block Gauss–Seidel over an island's rows at the velocity level: in each
// sweep the constraint block solved directly, then the friction rows, then
// the normals, projected one by one. Returns the sweeps made and the last
// sweep's largest change (m/s).
struct Relaxed {
  int passes = 0;
  double largest = 0.0;
};
Relaxed relaxVelocities(RowSystem& R, const std::vector<int>& contactRows, DirectBlock& block,
                        const ContactSettings& settings, Eigen::VectorXd& v);
// The same sweeps on the contact rows alone, with the island's constraints
// eliminated: the Schur complement S = J_c W J_cᵀ − G K⁻¹ Gᵀ (G = J_c W J_bᵀ,
// K = J_b W J_bᵀ) is each contact row's response with the constraints held,
// so a contact on a rope feels the whole rope and its loads at once, where
// the block sweeps above let it feel only its own particle until the next
// constraint solve (a 2 g bead of a rope holding kilograms). Dense in the
// contact rows: for islands of up to kReducedRows of them.
constexpr int kReducedRows = 1500;
Relaxed relaxReduced(RowSystem& R, const std::vector<int>& contactRows, DirectBlock& block,
                     const ContactSettings& settings, Eigen::VectorXd& v);
// The projection: Newton steps of the constraint block in turn with
// Gauss–Seidel pushes of the normals out of overlap, until every error is
// within the slop. Returns the passes made and the last pass's largest error.
Relaxed projectPositions(RowSystem& R, const std::vector<int>& contactRows, DirectBlock& block,
                         const ContactSettings& settings, Eigen::VectorXd& x);

}  // namespace particles::solve
