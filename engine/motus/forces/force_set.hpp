#pragma once
// The forces of a mechanical system, kept by kind in contiguous arrays: a kind the
// scene does not use is an empty vector and costs one branch, never a virtual call
// per particle.
#include <vector>

#include "motus/forces/inverse_square_gravity.hpp"
#include "motus/forces/linear_drag.hpp"
#include "motus/forces/pendulum_torque.hpp"
#include "motus/forces/spring.hpp"
#include "motus/forces/uniform_gravity.hpp"
#include "motus/vector.hpp"

namespace motus {

struct ForceSet {
  std::vector<UniformGravity> gravity;
  std::vector<Spring> springs;
  std::vector<LinearDrag> drag;
  std::vector<CentralGravity> central_gravity;
  std::vector<MutualGravity> mutual_gravity;
  std::vector<PendulumTorque> pendulums;

  // F += every force at (t, x, v). Inline, so that a caller that knows d (and, for one body,
  // the masses' size) at compile time gets loops with known bounds. m: the masses (a Vector,
  // or a fixed-size vector of one).
  template <class Masses>
  void add_forces(double /*t*/, int d, const Masses& m, ConstVectorRef x, ConstVectorRef v, VectorRef F) const {
    for (const auto& f : gravity) f.add_forces(d, m, x, F);
    for (const auto& f : springs) f.add_forces(d, x, v, F);
    for (const auto& f : drag) f.add_forces(d, v, F);
    for (const auto& f : central_gravity) f.add_forces(d, m, x, F);
    for (const auto& f : mutual_gravity) f.add_forces(d, m, x, F);
    for (const auto& f : pendulums) f.add_forces(d, m, x, F);
  }
  // Total potential energy of the conservative forces (drag has none).
  double potential(int d, const Vector& m, ConstVectorRef x) const;
  bool empty() const;
  // Whether any force can be other than zero: a gravity of (0, 0), a drag or a spring of
  // coefficient 0, an attraction of strength 0 push nothing, and a step that has only those
  // need not evaluate them (it cost the ball gas 58–63 % a step: a kick and every velocity read
  // again). NaN counts as acting.
  bool acts() const;
};

}  // namespace motus
