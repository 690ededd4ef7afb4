// A plug-in whose integrators misbehave on purpose, for test_grade's plug-in errors:
// "bad:throws" throws, "bad:crashes" dereferences a null pointer, "bad:nan" answers NaN,
// "bad:keeps-h" is step doubling whose controller keeps a rejected step's size, "bad:shrinks-h"
// one whose controller halves every step, accepted or not (the sum of the steps never reaches the end);
// "bad:prints" is explicit Euler that prints a line per step, as a student's debugging does;
// "bad:exits" calls exit(0) at its first step; "bad:recurses" calls itself without end (a stack
// overflow).
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <stdexcept>

#include "motus/student/plugin.hpp"

namespace {

void throws(const student::FirstOrderSystem&, double, double, student::VectorInOut) {
  throw std::runtime_error("thrown on purpose");
}

void crashes(const student::FirstOrderSystem&, double, double, student::VectorInOut y) {
  *static_cast<volatile double*>(nullptr) = y[0];
}

void nan(const student::FirstOrderSystem&, double, double, student::VectorInOut y) {
  y.setConstant(std::numeric_limits<double>::quiet_NaN());
}

// An error estimate no tolerance accepts, and the same h again.
student::Vector rejected(const student::FirstOrderSystem&, double, double, student::VectorIn y, student::Vector& error) {
  error = student::Vector::Constant(y.size(), 1.0);
  return y;
}
double keeps_h(double h, double) { return h; }

// Every step accepted (an error of 0, and y left as it was), and the next one half as long.
student::Vector accepted(const student::FirstOrderSystem&, double, double, student::VectorIn y, student::Vector& error) {
  error = student::Vector::Zero(y.size());
  return y;
}
double halves_h(double h, double) { return h / 2; }

// A line on standard output per step, half through printf and half through std::cout.
void prints(const student::FirstOrderSystem& f, double t, double h, student::VectorInOut y) {
  if (static_cast<long>(t / h + 0.5) % 2 == 0) std::printf("bad:prints step at t = %g\n", t);
  else std::cout << "bad:prints step at t = " << t << "\n";
  y += h * f.derivative(t, y);
}

void exits(const student::FirstOrderSystem&, double, double, student::VectorInOut) { std::exit(0); }

// A recursion with no base case (a frame of locals the compiler cannot drop, and work after the
// call, so that the call stays a call).
void recurses(const student::FirstOrderSystem& f, double t, double h, student::VectorInOut y) {
  if (h == 0) return;  // (never: each call passes the same h on; only so that it is not "infinite recursion" to the compiler)
  volatile double frame[32];
  frame[0] = h;
  recurses(f, t, frame[0], y);
  y[0] += frame[0];
}

}  // namespace

MOTUS_PLUGIN("bad", "integrators that misbehave (test_grade)") {
  plugin.first_order("throws", 1, "throws std::runtime_error", throws);
  plugin.first_order("crashes", 1, "dereferences a null pointer", crashes);
  plugin.first_order("recurses", 1, "calls itself without end", recurses);
  plugin.first_order("nan", 1, "answers NaN", nan);
  plugin.adaptive("keeps-h", 5, "a controller that keeps a rejected step's size", rejected, keeps_h);
  plugin.adaptive("shrinks-h", 5, "a controller that halves every step", accepted, halves_h);
  plugin.first_order("prints", 1, "explicit Euler that prints a line per step", prints);
  plugin.first_order("exits", 1, "calls exit(0)", exits);
}
