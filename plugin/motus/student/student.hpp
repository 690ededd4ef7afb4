#pragma once
// What a student's code sees of motus: a few vector types and two kinds of system, as in
// the course — nothing to inherit from, no templates to learn. (The whole page:
// assignments/README.md.)
//
//   Vector       numbers you own:                       Vector k1 = f.derivative(t, y);
//   VectorIn     numbers you only read (any vector or expression: y + 0.5 * h * k1)
//   VectorInOut  numbers you change in place:            y += h * k1;
// All three are Eigen vectors (https://eigen.tuxfamily.org): +, −, * by a number, .dot(),
// .norm(), .squaredNorm(), .size(), [i], .segment(start, count) work as you expect.
#include <Eigen/Core>

#include "motus/external/external_parts.hpp"

namespace student {

using Vector = Eigen::VectorXd;
using VectorIn = const Eigen::Ref<const Eigen::VectorXd>&;
using VectorInOut = Eigen::Ref<Eigen::VectorXd>;

// A first-order system y' = f(t, y): the strange attractors, World2, or point masses seen
// as y = [x; v] with y' = [v; a].
class FirstOrderSystem {
public:
  explicit FirstOrderSystem(const motus::ExternalFirstOrder& f) : f_(f) {}
  // The number of state variables.
  int size() const { return f_.size; }
  // f(t, y).
  Vector derivative(double t, VectorIn y) const {
    Vector dydt(f_.size);
    f_.derivative(f_.self, t, y.data(), dydt.data());
    return dydt;
  }

private:
  const motus::ExternalFirstOrder& f_;
};

// Point masses moved by forces: x'' = a(t, x, v) = F/m. x and v hold every body's
// coordinates, body i's coordinate k at index i·d + k.
class MechanicalSystem {
public:
  MechanicalSystem(const motus::ExternalMechanical& s, const double* velocity = nullptr)
      : s_(s), velocity_(velocity) {}
  // The number of coordinates: bodies × dimensions.
  int size() const { return s_.size; }
  // a = F(t, x, v)/m.
  Vector acceleration(double t, VectorIn x, VectorIn v) const {
    Vector a(s_.size);
    s_.acceleration(s_.self, t, x.data(), v.data(), a.data());
    return a;
  }
  // a = F(t, x)/m, for a method that keeps no velocities (velocityless Verlet): forces that
  // depend on velocity (drag) see the velocity motus last reported. In any other method they
  // see v = 0 here (no drag, no spring damping): call acceleration(t, x, v) there.
  Vector acceleration(double t, VectorIn x) const {
    Vector a(s_.size);
    const Vector none = Vector::Zero(s_.size);
    s_.acceleration(s_.self, t, x.data(), velocity_ ? velocity_ : none.data(), a.data());
    return a;
  }

private:
  const motus::ExternalMechanical& s_;
  const double* velocity_;
};

}  // namespace student
