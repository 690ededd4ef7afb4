#include "motus/constrain/chain_solver.hpp"

#include <algorithm>
#include <cmath>

namespace motus {

ChainSolver::ChainSolver(int dimensions, const Vector& inverse_mass, const std::vector<StickConstraint>& sticks,
                         std::vector<StickChain> chains)
    : d_(dimensions), inverse_mass_(inverse_mass), chains_(std::move(chains)) {
  for (const auto& s : sticks) length_.push_back(s.length);
  size_t longest = 0;
  for (const auto& c : chains_) {
    longest = std::max(longest, c.sticks.size());
    double length = 0;
    for (int s : c.sticks) length += length_[static_cast<size_t>(s)];
    chain_length_.push_back(length);
  }
  unit_.resize(longest * static_cast<size_t>(d_));
  error_.resize(longest);
  pivot_.resize(longest);
  off_.resize(longest);
  rhs_.resize(longest);
  lambda_.resize(longest);
}

bool ChainSolver::iterate(double* x, double tolerance) {
  switch (d_) {
    case 1: return iterate_in<1>(x, tolerance);
    case 2: return iterate_in<2>(x, tolerance);
    default: return iterate_in<3>(x, tolerance);
  }
}

// A chain whose sticks have no direction (two ends at one point), or whose system rounding
// has made singular, gets one sweep of single-stick projections instead (what a sweep would
// have done), and Newton resumes from there at the next iteration.
template <int D>
void ChainSolver::sweep_chain(const StickChain& chain, double* x) const {
  for (size_t j = 0; j < chain.sticks.size(); ++j) {
    const int a = chain.bodies[j], b = chain.bodies[j + 1];
    const double wa = inverse_mass_[a], wb = inverse_mass_[b];
    double delta[D], length2 = 0;
    for (int k = 0; k < D; ++k) {
      delta[k] = x[D * b + k] - x[D * a + k];
      length2 += delta[k] * delta[k];
    }
    if (length2 == 0) continue;
    const double length = std::sqrt(length2);
    const double stretch = (length - length_[static_cast<size_t>(chain.sticks[j])]) / (length * (wa + wb));
    for (int k = 0; k < D; ++k) {
      x[D * a + k] += stretch * wa * delta[k];
      x[D * b + k] -= stretch * wb * delta[k];
    }
  }
}

template <int D>
bool ChainSolver::iterate_in(double* x, double tolerance) {
  bool all_exact = true;
  for (size_t c = 0; c < chains_.size(); ++c) {
    const StickChain& chain = chains_[c];
    const size_t m = chain.sticks.size();
    const int* q = chain.bodies.data();
    // The constraints and their directions, and how far the worst is from its length.
    double worst = 0;
    bool degenerate = false;
    for (size_t j = 0; j < m; ++j) {
      double* n = &unit_[D * j];
      double length2 = 0;
      for (int k = 0; k < D; ++k) {
        n[k] = x[D * q[j + 1] + k] - x[D * q[j] + k];
        length2 += n[k] * n[k];
      }
      const double length = std::sqrt(length2);
      const double rest = length_[static_cast<size_t>(chain.sticks[j])];
      error_[j] = length - rest;
      worst = std::max(worst, std::abs(error_[j]) / rest);
      if (length == 0) {
        degenerate = true;
        continue;
      }
      for (int k = 0; k < D; ++k) n[k] /= length;
    }
    if (worst <= tolerance) continue;  // exact already: leave it be
    all_exact = false;
    if (degenerate) {
      sweep_chain<D>(chain, x);
      continue;
    }
    // (J W Jᵀ) λ = −C by elimination down the chain and substitution back up. The matrix is
    // symmetric: diagonal w_j + w_{j+1}, and beside it e_j = −w_j n_{j−1}·n_j (at body j,
    // between sticks j − 1 and j).
    bool singular = false;
    for (size_t j = 0; j < m; ++j) {
      const double diagonal = inverse_mass_[q[j]] + inverse_mass_[q[j + 1]];
      if (j == 0) {
        pivot_[0] = diagonal;
        rhs_[0] = -error_[0];
      } else {
        double dot = 0;
        for (int k = 0; k < D; ++k) dot += unit_[D * (j - 1) + k] * unit_[D * j + k];
        const double e = off_[j] = -inverse_mass_[q[j]] * dot;
        const double f = e / pivot_[j - 1];
        pivot_[j] = diagonal - f * e;
        rhs_[j] = -error_[j] - f * rhs_[j - 1];
      }
      if (!(pivot_[j] > 0)) singular = true;  // (J W Jᵀ is positive definite: only rounding gets here)
    }
    if (singular) {
      sweep_chain<D>(chain, x);
      continue;
    }
    lambda_[m - 1] = rhs_[m - 1] / pivot_[m - 1];
    for (size_t j = m - 1; j-- > 0;) lambda_[j] = (rhs_[j] - off_[j + 1] * lambda_[j + 1]) / pivot_[j];
    // A Newton step that would move a body farther than the whole chain is long is no step to
    // take: the system is nearly singular. A chain pulled straight between two pins it cannot
    // reach has one constraint too many along its line (its errors cannot all vanish), and its λ
    // was huge: the bodies were flung metres a step, Verlet read that as speed, and the energy
    // grew without end. A sweep then does what a sweep does (a stretched chain stays stretched,
    // as in the peers), and Newton resumes at the next iteration.
    double farthest = 0;
    for (size_t j = 0; j < m; ++j)
      farthest = std::max(farthest, std::abs(lambda_[j]) * std::max(inverse_mass_[q[j]], inverse_mass_[q[j + 1]]));
    const bool too_far = !(farthest <= chain_length_[c]);  // (NaN too)
    if (too_far) {
      sweep_chain<D>(chain, x);
      continue;
    }
    // x ← x + W Jᵀ λ: stick j pulls body j along −n_j and body j + 1 along +n_j.
    for (size_t j = 0; j < m; ++j) {
      const double move_a = inverse_mass_[q[j]] * lambda_[j], move_b = inverse_mass_[q[j + 1]] * lambda_[j];
      for (int k = 0; k < D; ++k) {
        x[D * q[j] + k] -= move_a * unit_[D * j + k];
        x[D * q[j + 1] + k] += move_b * unit_[D * j + k];
      }
    }
  }
  return all_exact;
}

}  // namespace motus
