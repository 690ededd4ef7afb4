#pragma once
// Sorting a step's events into time order, in linear time: a counting sort into time slices
// of about four events each, then a std::sort of each slice. The order is exactly
// std::sort's (the slices follow one another in time, and each is sorted by the same <),
// so the events, and the run, do not depend on which sort was used.
//
// A big ball gas finds thousands of contacts at the start of a step (about one ball in a
// hundred has one); one std::sort of them all is n log n: at a million balls 0.7–0.8 cycles
// per ball-step, against 0.2 by slices (bench_collisions' gas, timed by phase).
#include <algorithm>
#include <cstddef>
#include <vector>

namespace motus {

// From this many events on, by slices (below it one std::sort is as fast).
constexpr std::size_t kSliceSortFrom = 1024;

// Sorts events (each with a time .t in [0, horizon], and an operator<) by <. `scratch` and
// `starts` are the caller's buffers, kept from step to step so that a step allocates nothing.
template <class Event>
void sort_by_time(std::vector<Event>& events, double horizon, std::vector<Event>& scratch, std::vector<int>& starts) {
  const std::size_t n = events.size();
  if (n < kSliceSortFrom) {
    std::sort(events.begin(), events.end());
    return;
  }
  const int slices = static_cast<int>(n / 4);
  const double per_second = slices / horizon;
  // (Clamped as a double before the conversion: a time a hair outside [0, horizon] from
  // rounding, or a NaN, goes to an end slice, and the slice's std::sort still orders it.)
  auto slice_of = [per_second, last = static_cast<double>(slices - 1)](double t) {
    return static_cast<int>(std::min(std::max(0.0, t * per_second), last));
  };
  // Counted into slot s + 2, summed, placed from slot s + 1: slice s is then
  // scratch[starts[s] .. starts[s + 1]).
  starts.assign(static_cast<std::size_t>(slices) + 2, 0);
  int* start = starts.data();
  for (const Event& e : events) ++start[slice_of(e.t) + 2];
  for (int s = 2; s < slices + 2; ++s) start[s] += start[s - 1];
  scratch.resize(n);
  for (const Event& e : events) scratch[static_cast<std::size_t>(start[slice_of(e.t) + 1]++)] = e;
  for (int s = 0; s < slices; ++s) std::sort(scratch.begin() + start[s], scratch.begin() + start[s + 1]);
  events.swap(scratch);
}

}  // namespace motus
