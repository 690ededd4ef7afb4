#pragma once
// The numbers the ball collisions (ball_collisions.hpp and the files beside it) are tuned with, each
// with why it is what it is. For those files alone.
#include <cstddef>

#include "motus/collide/time_of_impact.hpp"

namespace motus::ball_collisions_tuning {

// After this many collisions in one step, a ball's inelastic contacts (e < 1) become
// perfectly inelastic (e = 0): it stops the endless chatter of "inelastic collapse" (a
// ball trapped between two others losing a fraction of its speed at every touch)
// without touching elastic scenes.
constexpr unsigned kCollapseLimit = 64;

// A cluster settled at once (settle_cluster) has at most this many balls (the rest of a big
// pile is left to the events), and is settled when no contact approaches faster than this
// fraction of its fastest speed.
constexpr size_t kClusterBalls = 128;
constexpr double kSettled = 1e-14;
// The clusters' work in a step (contact_cluster.hpp's units, a contact's update each) is at most
// this many times the events' limit: a heap of thousands of balls with little restitution under
// gravity is more than clusters of 128 can settle, and without a bound its clusters took millions
// of sweeps each (a run that had failed at the events' limit went on for minutes). Once it is
// spent, the contacts go one at a time, perfectly inelastic, as before. (The bouncing balls with
// every e = 0.3 took at most 106,000 in a step: 41 times their limit of 2,600 events.)
constexpr long kClusterWorkPerEvent = 200;

// The rows of grid cells (three cells side by side along x) that a ball's pairs are listed from,
// besides its own: the forward half of the 3^(D−1) rows around it (build_grid), 1 in 2-D, 4 in 3-D.
template <int D>
constexpr int kForwardRows = ([] {
  int rows = 1;
  for (int k = 1; k < D; ++k) rows *= 3;
  return (rows - 1) / 2;
})();

// Overlap smaller than this fraction of the contact distance is rounding, not overlap.
constexpr double kOverlapSlack = kRoundingOverlap;  // (time_of_impact.hpp: the same rounding)
// Bodies whose gap is at most this fraction of their contact distance touch, for a plug-in's
// time of impact (its rounding and the engine's differ by a few units in the last place).
constexpr double kTouching = 1e-9;
// How far from touching a plug-in's time of impact may leave two bodies, as a fraction of their
// contact distance, plus the rounding of their positions' size: a root computed in any sensible
// way (a quadratic's, with its cancellation) is far closer; a wrong one (the radius left out, the
// later root) is off by the radius or more.
constexpr double kAtContact = 1e-6;
constexpr double kPositionRounding = 1e-12;

// Up to this many grid cells (half a megabyte of starts: in L2) the grid is counting-sorted
// in one level; beyond it, in two (see build_grid).
constexpr int kSmallGrid = 1 << 17;

// From this many bodies on (their x and v alone fill most of a 1 MB L2 cache), the passes
// that jump around — the listed pairs, and the events — fetch what they will need from
// memory ahead of time. Below it everything is in cache and a prefetch only costs.
constexpr int kPrefetchFrom = 1 << 14;
// The listed pairs' balls are fetched this many pairs ahead (about one memory latency ahead):
// a pair's second ball may be a row (in 3-D a plane) of balls away from its first.
constexpr int kPairPrefetch = 32;

// Building the lists goes through the grid's candidates this many at a time (a few kB: in L1),
// copying each range of balls kWindow at a time (a longer range is copied one by one); each
// step tests the listed pairs this many at a time.
constexpr int kBatch = 256;
constexpr int kWindow = 4;

// The lists' skin covers about this many steps of the fastest slow ball: a wider skin lists
// more pairs to test every step, a narrower one builds the lists more often. (Eight was the
// fastest in bench_collisions' gases, 2-D and 3-D, from 10^3 to 10^6 balls; four and sixteen
// were slower at every size.) It is at most the largest radius, unless a slow ball moves farther
// than half of that in one step: a skin of twice the step's sweep holds for that step.
constexpr double kSkinSteps = 8;

// A build sorts the pairs of each of the pair pass's batches into this many classes by their
// gap then (0 to skin, in equal parts): a pair whose balls were a gap g apart cannot touch
// until they have closed it, so a step tests only the classes the balls can have closed by its
// end — the nearest on the lists' first step, all of them on their last (about two thirds of
// the pairs over the lists' life).
constexpr int kGapClasses = 4;

// A correction of a ball's position larger than this fraction of the grid's cell takes the
// ball off the lists (it may now be near balls that are not on them); smaller ones (rounding)
// count against the lists' half skin, as the distance the ball moved.
constexpr double kNudge = 1e-9;

// The start's settling (settle_overlaps) sweeps the walls and the pairs at most this many times, and
// makes at most about this many tests (of a pair, or of a body and a wall, and a build of the lists
// as kSettleBuildWork a body) in all: a start with room for its balls is apart long before
// (measured: three balls of r = 0.5 m in a row 0.1 m into each other, pushed into a wall, in 92
// sweeps; a row of 20 in 4,239; 400 balls on a square lattice 0.1 m into each other, in a corner
// of their box, in 9,919, 0.15 s), one without room would go on for ever (six in a box 5 m wide:
// stopped by the sweeps, in 15 ms; 2,500 on a lattice of 0.79 m in a box of 40 m, by the tests,
// in 0.5 s). What is left the steps remove, a step at a time, as before.
constexpr int kSettleSweeps = 100'000;
constexpr long kSettleWork = 50'000'000;
constexpr long kSettleBuildWork = 10;  // (a build of the lists, in tests a body: it looks into its cells)

// A ball that moves more than this many radii in a step crosses others, and a gas of them needs
// many contacts a step: that, not overlap, is the likelier cause of too many.
constexpr double kFastRadii = 4;

// With this many fast balls or more at a step's start, they find each other in a grid of their
// paths (path_grid.hpp) rather than each testing all the others.
constexpr size_t kPathGridFrom = 32;
// The grid of paths cuts the time a typical fast ball's path lasts (to its first wall contact,
// or the step's end) into at most this many slabs: one a diameter of the path.
constexpr double kPathSlabs = 8;
// When stale entries (paths that contacts have changed since) make the grid of paths this
// many times as big as when it was last entered whole, it is entered whole again, from now.
constexpr size_t kPathGridGrowth = 4;

}  // namespace motus::ball_collisions_tuning
