#pragma once
// Where an integrator keeps its stages (k1, k2, …, the intermediate states) during a step.
// For a system that knows its size N at compile time (static_size_of, first_order_system.hpp)
// a StageVector<N> is a fixed-size array: each step makes a fresh set on the stack, which the
// compiler keeps in registers, and every loop over it has a bound known at compile time. For
// any other system (N = Eigen::Dynamic) it is a Vector that resize() sized once. Neither
// allocates during a step.
// The Runge–Kutta family (euler, midpoint, rk4, rk45, …) updates its stages with plain loops
// over i (y_stage[i] = y[i] + 0.5 * h * k1[i]) rather than Eigen's expressions: on the course's
// small systems the loops are faster, as expressions pay set-up costs on three numbers
// (bench/lorenz_rk4_loops_vs_eigen.cpp, in bench_integrators).
#include <Eigen/Core>

namespace motus {

template <int N>
using StageVector = Eigen::Matrix<double, N, 1>;

}  // namespace motus
