#include "motus/constrain/constraint_projection.hpp"

namespace motus {

ConstraintProjection::ConstraintProjection(int dimensions, const Vector& inverse_mass, std::vector<double> radius,
                                           std::vector<StickConstraint> sticks, std::vector<PinConstraint> pins,
                                           const Colliders& colliders, int iterations)
    : d_(dimensions), inverse_mass_(inverse_mass), radius_(std::move(radius)), sticks_(std::move(sticks)),
      pins_(std::move(pins)), colliders_(colliders), iterations_(iterations) {
  for (const auto& p : pins_) inverse_mass_[p.body] = 0;
}

void ConstraintProjection::project(VectorRef) {}  // TODO(helper): Jakobsen relaxation

double ConstraintProjection::max_relative_stick_error(ConstVectorRef) const { return 0; }

bool ConstraintProjection::pinned(int body) const { return inverse_mass_[body] == 0; }

}  // namespace motus
