#!/bin/sh
# Regenerates the README's pictures in docs/pictures/ with `motus render` (docs/render.md), `motus compare`,
# `motus bench precision` and `motus stress` (docs/constraints_cost.sh makes constraints_cost.png).
#   docs/make_pictures.sh              uses build/motus
#   MOTUS=build-x/motus docs/make_pictures.sh
# Needs ffmpeg (for the GIFs). Every file stays well under 200 KB.
set -eu
cd "$(dirname "$0")/.."
MOTUS=${MOTUS:-build/motus}
OUT=docs/pictures
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
mkdir -p "$OUT"

# An animated GIF: NAME SCENE [motus render options...]
gif() {
  name=$1 scene=$2
  shift 2
  "$MOTUS" render "$scene" --out "$WORK/$name" --video gif "$@" >/dev/null
  cp "$WORK/$name/$scene.gif" "$OUT/$name.gif"
  echo "$OUT/$name.gif  $(wc -c <"$OUT/$name.gif") bytes"
}

# The last frame as a PNG: NAME SCENE [motus render options...]
png() {
  name=$1 scene=$2
  shift 2
  "$MOTUS" render "$scene" --out "$WORK/$name" "$@" >/dev/null
  cp "$(ls "$WORK/$name"/frame_*.png | tail -n 1)" "$OUT/$name.png"
  echo "$OUT/$name.png  $(wc -c <"$OUT/$name.png") bytes"
}

# The course's spring (m = 10, k = 5), one period (2 pi sqrt(2) = 8.9 s) with velocity Verlet at dt = 0.02
# (the scene's own explicit Euler at h = 1 gains energy every step: `motus run spring` shows the table).
gif spring spring --size 320x160 --fps 10 --duration 8.9 --set integrator=velocity-verlet --set dt=0.02
gif bouncing_balls bouncing_balls --size 240x240 --fps 10 --duration 5
gif newtons_cradle newtons_cradle --size 320x140 --fps 15 --duration 3
gif ragdoll ragdoll --size 300x210 --fps 15 --duration 4
png cloth cloth --size 400x300 --fps 1 --duration 3
png lorenz lorenz --size 400x300 --fps 1 --duration 30
png world2 world2 --size 560x320 --fps 0.05 --duration 200

# Newton's cradle in motus, Box2D and Bullet side by side at the start and the end: the picture
# every `motus compare` report has (first_and_last.png).
"$MOTUS" compare newtons_cradle --size 300x150 --out "$WORK/compare" >/dev/null
cp "$WORK/compare/first_and_last.png" "$OUT/compare_newtons_cradle.png"
echo "$OUT/compare_newtons_cradle.png  $(wc -c <"$OUT/compare_newtons_cradle.png") bytes"

# Run time against error on one Kepler orbit, beside Boost.Odeint (`motus bench precision`, README's tour, step 4).
"$MOTUS" bench precision kepler --peers odeint --out "$WORK/precision" >/dev/null
cp "$WORK/precision/error_against_time.png" "$OUT/precision_kepler_time.png"
echo "$OUT/precision_kepler_time.png  $(wc -c <"$OUT/precision_kepler_time.png") bytes"

# The stress test's long run on the oscillator (`motus stress`, docs/cli.md): the energy error over 10^5 steps.
"$MOTUS" stress oscillator --out "$WORK/stress" >/dev/null
cp "$WORK/stress/drift.png" "$OUT/stress_oscillator_drift.png"
echo "$OUT/stress_oscillator_drift.png  $(wc -c <"$OUT/stress_oscillator_drift.png") bytes"
