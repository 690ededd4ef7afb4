#pragma once
// Work against precision (docs/cli.md, `motus bench precision`): every method of a run — motus's
// own integrators, Odeint's steppers, Box2D and Bullet — is one Curve of Points, each point one
// step size or tolerance with the error it reached at the end time, the work it took
// (derivative evaluations) and its run time.
#include <functional>
#include <string>
#include <vector>

#include "motus/scene.hpp"

namespace motus::precision {

struct Point {
  double h = 0;          // the step; for an adaptive method the first step tried
  double tolerance = 0;  // rtol = atol of an adaptive method; 0 for a fixed-step one
  long steps = 0;        // accepted steps
  long evaluations = 0;  // derivative (force) evaluations, rejected attempts included
  double t_end = 0;      // where the run ended, at which the error is taken
  double error = 0;      // max over the state of |y − y_exact| at t_end (inf when it blew up)
  double seconds = 0;    // the fastest of the timed runs (one per timing round: sweep_in_rounds)
  double median_seconds = 0;  // their median
  std::string failed;    // why this point could not be measured, or ""
};

struct Curve {
  std::string method;       // "dop853", "odeint:runge_kutta_fehlberg78", "box2d", "student:rk4"
  std::string engine;       // "motus", "odeint", "box2d", "bullet", or a plug-in's name
  std::string description;  // one line
  bool adaptive = false;
  std::string unsupported;  // why the method cannot run this scene, or ""
  std::vector<Point> points;
};

// What every method sweeps, and how each point is timed.
struct Sweep {
  double end = 0;      // the end time (the scene starts at its start_time)
  double dt = 0;       // the scene's step: fixed steps dt/2^k, and the first step of adaptive runs
  int levels = 8;      // fixed-step methods: h = dt / 2^k, k = 0 … levels − 1
  int per_decade = 3;  // adaptive methods: rtol = atol = 10^(−3 − j/per_decade) down to 1e-13
  int repeats = 9;     // timing rounds (after one untimed round): a timed run per point each; the fastest counts
  // Which round a sweep is run for (sweep_in_rounds): 0, the untimed one, whose numbers (error, steps,
  // evaluations) every point reports; 1 … repeats, the timed ones. A sweep runs every point once per
  // call and gives that run's time as the point's (round 0's counts only when repeats is 0).
  int round = 0;
  // Called after every point with its nominal steps (a fixed step's run length; an adaptive point's
  // first-step count, end/dt, a guess), so that a progress bar can weigh the points by their work:
  // each level has twice the steps of the one before. May be empty.
  std::function<void(double steps)> point_done;
  // Called every 65,536 steps of a point's untimed run (a safe point to stop at: Ctrl-C waited for a
  // point of 10¹³ steps to end), may be empty. Never in a timed run.
  std::function<void()> now_and_then;
  // Whether this call's runs are timed ones (their time is a point's).
  bool timed() const { return round > 0 || repeats == 0; }
};

// The fixed steps dt/2^k; where only reference states are known (no formula for every t), each
// shortened to the nearest that divides the run, so that the steps land on the reference time —
// for motus's methods and Odeint's alike.
std::vector<double> fixed_steps(const SceneDescription& scene, const Sweep& sweep);
std::vector<double> tolerances(const Sweep& sweep);
// The steps of a run of step h over the sweep (fixed_step_count from the scene's start): a point's
// work, for the progress (Sweep::point_done).
double nominal_steps(const SceneDescription& scene, const Sweep& sweep, double h);

// The peers' steps (Box2D and Bullet run at the frame rates of games): 1/30, 1/60, … 1/960 s.
std::vector<double> engine_steps();

}  // namespace motus::precision
