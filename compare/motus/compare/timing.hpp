#pragma once
// How motus times a run: the CPU time of the process (clock_gettime(CLOCK_PROCESS_CPUTIME_ID)),
// not the wall clock, so that time spent waiting for a core on a busy machine is not counted;
// and a time is never one measurement but several rounds of the same work, summarized by their
// minimum (the run least disturbed by everything else on the machine) with the median and the
// largest beside it (how much the rounds disagreed).
#include <algorithm>
#include <cmath>
#include <ctime>
#include <vector>

namespace motus::compare {

// CPU seconds used by this process so far (every thread), to the nanosecond.
inline double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Timings {
  double min = 0, median = 0, max = 0;  // 0 when there were no rounds
  int rounds = 0;
  // (max − min) / min: how far apart the rounds were.
  double spread() const { return min > 0 ? (max - min) / min : 0; }
};

// The minimum, median (the mean of the middle two for an even count) and maximum of `rounds`.
inline Timings summarize(std::vector<double> rounds) {
  Timings t;
  t.rounds = static_cast<int>(rounds.size());
  if (rounds.empty()) return t;
  std::sort(rounds.begin(), rounds.end());
  const size_t n = rounds.size();
  t.min = rounds.front();
  t.max = rounds.back();
  t.median = n % 2 ? rounds[n / 2] : 0.5 * (rounds[n / 2 - 1] + rounds[n / 2]);
  return t;
}

// Which of `engines` takes turn `turn` of timing round `round` (both from 0): every engine once a round,
// each round beginning one engine further on, so that a slow spell of a shared machine — at a round's
// start, say — falls on every engine alike rather than always on the same one. (`motus compare`'s
// rounds, and `motus bench precision`'s, whose "engines" are its methods.)
inline size_t taking_turns(size_t engines, size_t round, size_t turn) { return (turn + round) % engines; }

// The default number of timing rounds: kMostRounds, or as many as fit in `budget` CPU seconds
// when one round takes `seconds_per_round` — at least one. `motus compare` gives a round (every
// engine once) kCompareBudget: a small scene gets all five and stays well under a second, the
// cloth (about 1.5 s a round) two; `motus run` gives its runs kRunBudget, so that a run of a
// quarter of a second is not made to take more than a second.
constexpr int kMostRounds = 5;
constexpr double kCompareBudget = 3.0;
constexpr double kRunBudget = 1.0;
inline int auto_rounds(double seconds_per_round, double budget) {
  if (!(seconds_per_round > 0)) return kMostRounds;
  return static_cast<int>(std::clamp(std::floor(budget / seconds_per_round), 1.0, double(kMostRounds)));
}

}  // namespace motus::compare
