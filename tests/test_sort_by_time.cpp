// sort_by_time (engine/motus/collide/sort_by_time.hpp) against std::sort: the same order,
// element for element, on the events a step finds — times spread over the step, many of them
// equal (contacts at the same instant, as in Newton's cradle, ordered then by their bodies),
// times at the step's two ends, and a time a hair outside it from rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "motus/collide/sort_by_time.hpp"

namespace {

// An event as the collision pass has it: a time, then its bodies to break ties.
struct Event {
  double t;
  int i, other;
  bool operator<(const Event& e) const {
    if (t != e.t) return t < e.t;
    if (i != e.i) return i < e.i;
    return other < e.other;
  }
  bool operator==(const Event& e) const { return t == e.t && i == e.i && other == e.other; }
};

std::vector<Event> step_events(int n, double h, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> time(0, h);
  std::uniform_int_distribution<int> body(0, 50);
  std::vector<Event> events;
  for (int e = 0; e < n; ++e) {
    double t = time(random);
    switch (e % 10) {
      case 0: t = 0; break;                                // at the step's start
      case 1: t = h; break;                                // at its end
      case 2: t = h / 3; break;                            // many at one instant
      case 3: t = std::nextafter(h, 2 * h); break;        // a hair past the end (rounding)
      default: break;
    }
    events.push_back({t, body(random), body(random) - 10});
  }
  return events;
}

TEST(SortByTime, GivesStdSortsOrderOnAStepsEvents) {
  const double h = 1.0 / 60;
  std::vector<Event> scratch;
  std::vector<int> starts;
  // Below the slices' threshold (one std::sort), at it, and well above it, twice each with
  // the same buffers (as step after step).
  for (const int n : {10, static_cast<int>(motus::kSliceSortFrom), 5000, 5000, 100000}) {
    for (const unsigned seed : {1u, 2u}) {
      std::vector<Event> events = step_events(n, h, seed + static_cast<unsigned>(n));
      std::vector<Event> expected = events;
      std::sort(expected.begin(), expected.end());
      motus::sort_by_time(events, h, scratch, starts);
      ASSERT_EQ(events.size(), expected.size());
      EXPECT_TRUE(events == expected) << n << " events, seed " << seed;
    }
  }
}

TEST(SortByTime, AllAtOneInstantGoByTheirBodies) {
  // Every event in one slice: the slices' std::sort alone orders them, by the bodies.
  std::vector<Event> events;
  for (int e = 0; e < 3000; ++e) events.push_back({0.25, (e * 7919) % 3000, e % 3});
  std::vector<Event> expected = events;
  std::sort(expected.begin(), expected.end());
  std::vector<Event> scratch;
  std::vector<int> starts;
  motus::sort_by_time(events, 1.0, scratch, starts);
  EXPECT_TRUE(events == expected);
}

}  // namespace
