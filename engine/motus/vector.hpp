#pragma once
// One vector type for all state: a contiguous array of doubles (Eigen::VectorXd).
// A mechanical state of N particles in d dimensions stores particle i's
// coordinate k at index i*d + k.
#include <Eigen/Core>

namespace motus {

using Vector = Eigen::VectorXd;
using VectorRef = Eigen::Ref<Vector>;
using ConstVectorRef = Eigen::Ref<const Vector>;

}  // namespace motus
