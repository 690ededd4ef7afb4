#pragma once
// The timing rounds of `motus bench precision`, taken as `motus compare` times its engines. First
// one untimed round, in which every method runs each of its points once: the numbers each point
// reports (its error, steps and evaluations). Then Sweep::repeats timed rounds, in which every
// method runs each of its points once more, timed, the methods taking turns, each round beginning
// one method further on: a slow spell of a shared machine then falls on every engine alike, not
// on whichever happened to be running (motus's curves all came first, and Odeint's after them).
// A point's time is the fastest of its timed runs, with their median beside it (run_times.hpp).
#include <functional>
#include <vector>

#include "motus/precision/work_precision.hpp"

namespace motus::precision {

// One method's sweep — or several methods': Odeint's steppers come as one — run for the round
// that Sweep::round names: its curves, each point run once.
using SweepOf = std::function<std::vector<Curve>(const Sweep&)>;

// Every sweep's curves, in the sweeps' order, with the untimed round's numbers and the timed
// rounds' times. A sweep that has nothing to time (every curve unsupported, every point failed)
// runs in the untimed round only.
std::vector<Curve> sweep_in_rounds(const std::vector<SweepOf>& sweeps, const Sweep& sweep);

}  // namespace motus::precision
