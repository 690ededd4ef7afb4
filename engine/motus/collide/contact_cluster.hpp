#pragma once
// Inelastic collapse, and its cure. Contacts taken one at a time (ball_collisions.hpp) settle a
// ball pressed between others, or into a wall, only in the limit: each perfectly inelastic
// contact stops the approach along its own normal and starts one along its neighbour's, and for
// two normals at an angle θ the approach left shrinks by about cos²θ a round — thousands of
// contacts at one instant for a ball in a narrow wedge (the bouncing balls with e = 0.8 failed
// that way). Taken together, the touching contacts of a cluster are one problem, as the peers'
// contact solvers pose it (a linear complementarity problem): impulses λ_c along the normals,
//   λ_c ≥ 0                       (a contact pushes, never pulls),
//   u_c' = u_c + Σ_d A_cd λ_d ≥ 0  (afterwards no contact approaches: perfectly inelastic),
//   λ_c · u_c' = 0                 (a contact that pushes is left at rest),
// where u_c = (v_b − v_a)·n_c is contact c's closing speed (< 0: approaching) and A_cd is what a
// unit impulse at d does to it: n_c·n_d times the inverse mass of each body the two share, signed
// by the sides the body is on.
//
// Solved by projected Gauss–Seidel: contact after contact, the one-contact impulse of impulse.hpp
// with e = 0, but taken as a change of the contact's running total, which is never let below
// zero (so a contact may take back what it gave) — the same loop as the events', over a handful
// of numbers in cache instead of a step's queue of events. And now and then (after 16 sweeps,
// 32, 64, …), the contacts pushing now are taken as the ones that push in the answer, and the
// equations A_SS λ_S = −u_S of just those are solved directly: if every λ comes out ≥ 0 and no
// contact approaches, that is the exact answer, however narrow the wedge.
//
// Momentum is kept (each impulse is equal and opposite, or taken by a wall), and kinetic energy
// can only fall: every Gauss–Seidel update is a perfectly inelastic contact, and the answer
// changes it by −½ λᵀAλ ≤ 0.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace motus {

template <int D>
class ContactCluster {
public:
  using Point = Eigen::Matrix<double, D, 1>;

  void clear() { bodies_.clear(), contacts_.clear(); }
  // A body of the cluster (its index in it is returned) and a contact between two of them, the
  // normal n pointing from a to b. a < 0: a wall (infinite mass), n pointing out of it.
  int add_body(const Point& velocity, double inverse_mass) {
    bodies_.push_back({velocity, velocity, inverse_mass});
    return static_cast<int>(bodies_.size()) - 1;
  }
  void add_contact(int a, int b, const Point& n) { contacts_.push_back({a, b, n, 0, 0}); }

  bool has_contact(int a, int b) const {
    for (const Contact& c : contacts_)
      if ((c.a == a && c.b == b) || (c.a == b && c.b == a)) return true;
    return false;
  }
  int bodies() const { return static_cast<int>(bodies_.size()); }
  int contacts() const { return static_cast<int>(contacts_.size()); }
  const Point& velocity(int body) const { return bodies_[static_cast<size_t>(body)].v; }
  double impulse(int contact) const { return contacts_[static_cast<size_t>(contact)].impulse; }
  int wall_side(int contact) const { return contacts_[static_cast<size_t>(contact)].a; }

  // Finds the impulses, and the velocities after them, taking its work from `budget` (a
  // contact's update is one; a direct solve of m contacts, m³/3) and stopping when that is spent.
  // Returns whether no contact is left approaching faster than `tolerance` (m/s); if not, the
  // velocities are the last sweep's, every contact's impulse still a push (momentum kept).
  bool settle(double tolerance, long& budget) {
    for (Contact& c : contacts_) {
      const double w = (c.a >= 0 ? body(c.a).inverse_mass : 0) + body(c.b).inverse_mass;
      c.effective_mass = w > 0 ? 1 / w : 0;  // (between two immovable bodies nothing changes)
    }
    for (long sweep = 1; budget > 0; ++sweep) {
      double worst = 0;
      for (Contact& c : contacts_) {
        const double u = closing(c, false);
        worst = std::max(worst, c.impulse > 0 ? std::abs(u) : -u);
        const double total = std::max(c.impulse - u * c.effective_mass, 0.0);
        push(c, total - c.impulse);
        c.impulse = total;
      }
      budget -= contacts();
      if (worst <= tolerance) return true;
      // (At sweeps 16, 32, 64, …: a solve costs up to a few hundred sweeps' work.)
      if (sweep >= kFirstSolve && (sweep & (sweep - 1)) == 0 && contacts() <= kDirectSolveUpTo) {
        const long m = pushing();
        budget -= m * m * m / 3;
        if (solve_pushing(tolerance)) return true;
      }
    }
    return settled(tolerance);
  }

private:
  struct Body {
    Point v0, v;  // before, and now
    double inverse_mass;
  };
  struct Contact {
    int a, b;
    Point n;
    double impulse, effective_mass;
  };
  // The first sweep after which the pushing contacts' equations are tried (and again after twice
  // as many, and so on), for clusters of up to how many contacts (a dense solve).
  static constexpr long kFirstSolve = 16;
  static constexpr int kDirectSolveUpTo = 256;

  Body& body(int i) { return bodies_[static_cast<size_t>(i)]; }
  // u = (v_b − v_a)·n, with the velocities now or before.
  double closing(const Contact& c, bool before) {
    const Point& vb = before ? body(c.b).v0 : body(c.b).v;
    if (c.a < 0) return vb.dot(c.n);
    return (vb - (before ? body(c.a).v0 : body(c.a).v)).dot(c.n);
  }
  // An impulse j along n: pushes b along it, a against it.
  void push(const Contact& c, double j) {
    if (j == 0) return;
    Body& b = body(c.b);
    b.v += (j * b.inverse_mass) * c.n;
    if (c.a >= 0) {
      Body& a = body(c.a);
      a.v -= (j * a.inverse_mass) * c.n;
    }
  }
  bool settled(double tolerance) {
    for (const Contact& c : contacts_) {
      const double u = closing(c, false);
      if (u < -tolerance || (c.impulse > 0 && u > tolerance)) return false;
    }
    return true;
  }

  // The contacts pushing now (λ > 0) taken as those that push in the answer: A_SS λ_S = −u_S,
  // from the velocities before. Kept if every λ_S ≥ 0 and no contact then approaches.
  long pushing() {
    pushing_.clear();
    for (int c = 0; c < contacts(); ++c)
      if (contacts_[static_cast<size_t>(c)].impulse > 0) pushing_.push_back(c);
    return static_cast<long>(pushing_.size());
  }
  bool solve_pushing(double tolerance) {  // (after pushing())
    const int m = static_cast<int>(pushing_.size());
    if (m == 0) return false;
    A_.setZero(m, m);
    rhs_.resize(m);
    for (int r = 0; r < m; ++r) {
      const Contact& c = contacts_[static_cast<size_t>(pushing_[static_cast<size_t>(r)])];
      rhs_[r] = -closing(c, true);
      for (int s = 0; s <= r; ++s) {
        const Contact& d = contacts_[static_cast<size_t>(pushing_[static_cast<size_t>(s)])];
        // What d's impulse does to c's closing speed, through each body they share.
        double a = 0;
        const double nn = c.n.dot(d.n);
        if (c.b == d.b) a += body(c.b).inverse_mass * nn;
        if (c.a >= 0 && c.a == d.a) a += body(c.a).inverse_mass * nn;
        if (c.a >= 0 && c.a == d.b) a -= body(c.a).inverse_mass * nn;
        if (d.a >= 0 && c.b == d.a) a -= body(c.b).inverse_mass * nn;
        A_(r, s) = A_(s, r) = a;
      }
    }
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(A_);
    if (ldlt.info() != Eigen::Success) return false;
    const Eigen::VectorXd lambda = ldlt.solve(rhs_);
    if (!lambda.allFinite() || lambda.minCoeff() < 0) return false;
    // The velocities that impulse gives, from those before; kept only if they settle it.
    saved_v_.clear(), saved_impulse_.clear();
    for (const Body& b : bodies_) saved_v_.push_back(b.v);
    for (const Contact& c : contacts_) saved_impulse_.push_back(c.impulse);
    for (Body& b : bodies_) b.v = b.v0;
    for (Contact& c : contacts_) c.impulse = 0;
    for (int r = 0; r < m; ++r) {
      Contact& c = contacts_[static_cast<size_t>(pushing_[static_cast<size_t>(r)])];
      c.impulse = lambda[r];
      push(c, lambda[r]);
    }
    if (settled(tolerance)) return true;
    // Not the answer: back to where the sweeps were.
    for (size_t i = 0; i < bodies_.size(); ++i) bodies_[i].v = saved_v_[i];
    for (size_t c = 0; c < contacts_.size(); ++c) contacts_[c].impulse = saved_impulse_[c];
    return false;
  }

  std::vector<Body> bodies_;
  std::vector<Contact> contacts_;
  std::vector<int> pushing_;
  std::vector<Point> saved_v_;
  std::vector<double> saved_impulse_;
  Eigen::MatrixXd A_;
  Eigen::VectorXd rhs_;
};

}  // namespace motus
