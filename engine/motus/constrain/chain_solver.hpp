#pragma once
// A chain of sticks solved all at once, instead of swept.
//
// A sweep moves one stick at a time, and a correction travels along a chain one stick per
// sweep: the error of a long chain falls slowly (docs/course.md, section 10). The chain's
// sticks can instead be projected together — Newton's method on all the constraints
// C_j(x) = |x_{j+1} − x_j| − L_j at once (Goldenthal et al.'s "fast projection", 2007):
//
//     (J W Jᵀ) λ = −C,        x ← x + W Jᵀ λ,
//
// with J the constraints' gradients (row j: −n_j at body j, +n_j at body j + 1, n_j the unit
// vector along stick j) and W the inverse masses. Along a chain J W Jᵀ is tridiagonal —
// w_j + w_{j+1} on the diagonal, −w_j n_{j−1}·n_j beside it — and is solved in O(sticks)
// (the Thomas algorithm). Each iteration squares the error, so a few reach rounding; a pinned
// body (w = 0) decouples the two sides, and one stick alone takes one iteration, which is
// then exactly a sweep's projection.
#include <vector>

#include "motus/constrain/constraints.hpp"
#include "motus/constrain/stick_chains.hpp"
#include "motus/vector.hpp"

namespace motus {

class ChainSolver {
public:
  ChainSolver() = default;  // no chains
  // The chains' sticks must have w_a + w_b > 0 (find_stick_chains keeps only those).
  ChainSolver(int dimensions, const Vector& inverse_mass, const std::vector<StickConstraint>& sticks,
              std::vector<StickChain> chains);

  bool empty() const { return chains_.empty(); }
  // One Newton iteration on every chain that is not yet exact (largest |C_j|/L_j above
  // `tolerance`). Returns true when every chain already was: x was not touched. Allocates
  // nothing.
  bool iterate(double* x, double tolerance);

private:
  template <int D>
  bool iterate_in(double* x, double tolerance);
  template <int D>
  void sweep_chain(const StickChain& chain, double* x) const;

  int d_ = 1;
  Vector inverse_mass_;
  std::vector<double> length_;        // rest length of each stick
  std::vector<double> chain_length_;  // each chain's, the sum of its sticks' (a Newton step's bound)
  std::vector<StickChain> chains_;
  // Scratch, sized for the longest chain: the unit vectors n_j (d each), C_j, the matrix's
  // off-diagonal e_j, the elimination's pivots and right-hand side, λ.
  std::vector<double> unit_, error_, off_, pivot_, rhs_, lambda_;
};

}  // namespace motus
