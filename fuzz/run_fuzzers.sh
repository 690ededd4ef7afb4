#!/usr/bin/env bash
# Builds the fuzzers with clang (ASan + UBSan) and runs each for SECONDS (default 60), with the
# shipped scenes and fuzz/regressions/ (the past findings) as the seed corpus and the format's keywords as the dictionary. A finding
# (a crash, a hang, a sanitizer report) stops it with a non-zero status and leaves the input
# in BUILD_DIR/findings/. Used by ctest (a short run, SEED 1: the same inputs tried in the same
# order on every run, so that a test run passes or fails by the code alone) and by hand (a long
# one, a new random seed each time unless SEED is given):
#   fuzz/run_fuzzers.sh 1800 build/fuzz [SEED]
set -euo pipefail
seconds="${1:-60}"
here="$(cd "$(dirname "$0")" && pwd)"
build="${2:-$here/../build/fuzz}"
seed="${3:-0}"  # (libFuzzer's 0: a random seed)
mkdir -p "$build"  # (everything it writes goes in there)
cmake -S "$here" -B "$build" -DCMAKE_CXX_COMPILER=clang++ > "$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" -j"$(nproc)" > "$build/build.log" 2>&1 || { tail -40 "$build/build.log"; exit 1; }
mkdir -p "$build/findings"
status=0
for fuzzer in fuzz_load fuzz_step; do
  corpus="$build/corpus/$fuzzer"
  mkdir -p "$corpus"
  cp "$here"/../scenes/*.json "$corpus"/
  cp "$here"/regressions/* "$corpus"/   # every past finding is replayed first
  echo "== $fuzzer for ${seconds} s"
  # An input is a hang past 300 s. Slow is not stuck: an inelastic 196-ball gas at dt = 5 s runs to
  # the engine's 20,600 collisions in one step and stops (1.5 s in Release), which under the
  # sanitizers takes 30–75 s as the shared machine's load goes; at 30 s such inputs, found and
  # kept by earlier runs, failed later ones, and 120 s left a busier machine too little room.
  if ! "$build/$fuzzer" "$corpus" -dict="$here/scene.dict" -seed="$seed" -max_total_time="$seconds" -timeout=300 -rss_limit_mb=2048 \
       -max_len=65536 -artifact_prefix="$build/findings/$fuzzer-" -print_final_stats=1 2> "$build/$fuzzer.log"; then
    status=1
    tail -60 "$build/$fuzzer.log"
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb|Done [0-9]+ runs" "$build/$fuzzer.log" || true
done
exit $status
