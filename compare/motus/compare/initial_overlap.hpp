#pragma once
// A scene that starts overlapping, found from its description (compare's note, summary and column
// definitions, and run's note).

#include <string>

#include "motus/scene.hpp"

namespace motus::compare {

// Overlap in the scene as written: balls that start overlapping, and bodies that start into a wall
// (past a plane, out of a box or partly through its faces, within a segment's radius). motus moves
// them apart (and out) before the first step, as docs/scene-format.md's "Overlap" says, so a run
// shows none of it but a penetration the size of the start. Found from the description alone (a
// grid of 2·r_max cells, sorted: O(N log N), a million-ball lattice in well under a second), never
// from the engine. Overlaps below 10⁻⁶ of the contact distance (or of the radius: a rack of balls
// written to 7 digits) are rounding, not a mistake worth a word.
struct InitialOverlap {
  long pairs = 0;           // overlapping pairs of balls
  double pair_depth = 0;    // the deepest: r_a + r_b − distance, m
  int pair_a = -1, pair_b = -1;
  long into_walls = 0;      // bodies into a wall (each counted once)
  double wall_depth = 0;    // the deepest: radius − height above the wall's surface, m
  int wall_body = -1;
  std::string wall;         // "plane J", "box J" or "segment J"
  bool outside_box = false; // that body's centre is outside the box (not only its surface through a face)
  bool any() const { return pairs > 0 || into_walls > 0; }
};
InitialOverlap initial_overlap(const MechanicalDescription& m);

// The note's text for a scene that starts overlapping ("" when it does not), without "note: FILE: ":
// "bodies 0 and 1 start overlapping by 0.9 m (and 2 more pairs); motus moves them apart before the
// first step" — and, with `penetration_column`, ", and the penetration column counts that start".
std::string initial_overlap_note(const InitialOverlap& o, bool penetration_column);
std::string initial_overlap_note(const SceneDescription& scene, bool penetration_column);

}  // namespace motus::compare
