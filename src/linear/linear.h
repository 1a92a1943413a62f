#pragma once
// The engine's internal sparse linear algebra (src/linear, not installed, not
// part of include/particles). One copy of each piece, shared by the
// constraint solve (src/constraint_solver.cpp) and implicit Euler:
//
// - constraint_rows.h   ConstraintRows: the rows of J = ∂C/∂q and J̇ of every
//                       constraint at one phase, gathered into compressed
//                       arrays (one 2-vector block per particle of a row), with
//                       the products J W Jᵀ y, Jᵀ λ and J v that the solves need.
// - symmetric_pattern.h SymmetricPattern: the sparsity pattern of a symmetric
//                       matrix stored as the upper triangle of P S Pᵀ (P an AMD
//                       fill-reducing ordering or the identity), built once per
//                       structure, and the slot lookup that tells where entry
//                       (r, c) sits in the value array, so that each step only
//                       writes values.
// - ldlt.h              Ldlt: sparse LDLᵀ (Eigen's SimplicialLDLT, public API)
//                       of such a stored, already permuted triangle: the
//                       symbolic analysis once per pattern, the numeric
//                       factorisation each step, an optional diagonal shift.
// - tridiagonal.h       Tridiagonal: the O(m) LDLᵀ of a symmetric tridiagonal
//                       matrix (a chain's J W Jᵀ), with ldlt.h's interface.
// - conjugate_gradient.h conjugateGradient(): preconditioned CG over a
//                       matrix-free operator and a preconditioner (any callables),
//                       allocation-free with its scratch kept by the caller.
#include "linear/conjugate_gradient.h"
#include "linear/constraint_rows.h"
#include "linear/ldlt.h"
#include "linear/symmetric_pattern.h"
#include "linear/tridiagonal.h"
