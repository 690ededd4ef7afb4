#include "motus/systems/mechanical_system.hpp"

#include <stdexcept>

#include <Eigen/Geometry>  // Vector3d::cross (declared by Eigen/Core, defined here)

namespace motus {

MechanicalSystem::MechanicalSystem(int dimensions, std::vector<double> masses, ForceSet forces)
    : d_(dimensions), mass_(Eigen::Map<Vector>(masses.data(), static_cast<Eigen::Index>(masses.size()))),
      forces_(std::move(forces)) {
  if (d_ < 1 || d_ > 3) throw std::invalid_argument("a mechanical system has 1, 2 or 3 dimensions");
  for (double m : masses)
    if (!(m > 0)) throw std::invalid_argument("every mass must be > 0");
  inverse_mass_ = mass_.cwiseInverse();
  coordinate_inverse_mass_.resize(static_cast<Eigen::Index>(masses.size()) * d_);
  for (Eigen::Index i = 0; i < mass_.size(); ++i) coordinate_inverse_mass_.segment(i * d_, d_).setConstant(inverse_mass_[i]);
  one_mass_[0] = mass_.size() > 0 ? mass_[0] : 1.0;
}

void MechanicalSystem::acceleration(double t, ConstVectorRef x, ConstVectorRef v, VectorRef a) {
  ++evaluations;
  a.setZero();
  forces_.add_forces(t, d_, mass_, x, v, a);  // a holds F for now
  a.array() *= coordinate_inverse_mass_.array();  // a_ik = F_ik · (1/m_i), in one pass
}

double MechanicalSystem::kinetic_energy(ConstVectorRef v) const {
  double e = 0;
  for (int i = 0; i < particles(); ++i) e += 0.5 * mass_[i] * v.segment(i * d_, d_).squaredNorm();
  return e;
}

double MechanicalSystem::potential_energy(ConstVectorRef x) const { return forces_.potential(d_, mass_, x); }

Vector MechanicalSystem::momentum(ConstVectorRef v) const {
  Vector p = Vector::Zero(d_);
  for (int i = 0; i < particles(); ++i) p += mass_[i] * v.segment(i * d_, d_);
  return p;
}

Vector MechanicalSystem::angular_momentum(ConstVectorRef x, ConstVectorRef v) const {
  if (d_ == 1) return Vector(0);
  if (d_ == 2) {
    Vector l = Vector::Zero(1);
    for (int i = 0; i < particles(); ++i)
      l[0] += mass_[i] * (x[2 * i] * v[2 * i + 1] - x[2 * i + 1] * v[2 * i]);
    return l;
  }
  Eigen::Vector3d l = Eigen::Vector3d::Zero();
  for (int i = 0; i < particles(); ++i) {
    Eigen::Vector3d r = x.segment<3>(3 * i), u = v.segment<3>(3 * i);
    l += mass_[i] * r.cross(u);
  }
  return l;
}

}  // namespace motus
