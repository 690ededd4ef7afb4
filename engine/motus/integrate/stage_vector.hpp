#pragma once
// Where an integrator keeps its stages (k1, k2, …, the intermediate states) during a step.
// For a system that knows its size N at compile time (static_size_of, first_order_system.hpp)
// a StageVector<N> is a fixed-size array: each step makes a fresh set on the stack, which the
// compiler keeps in registers, and every loop over it has a bound known at compile time. For
// any other system (N = Eigen::Dynamic) it is a Vector that resize() sized once. Neither
// allocates during a step.
#include <Eigen/Core>

namespace motus {

template <int N>
using StageVector = Eigen::Matrix<double, N, 1>;

}  // namespace motus
