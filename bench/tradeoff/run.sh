#!/bin/sh
# Regenerates the speed-accuracy study: docs/tradeoff/tradeoff.csv, tradeoff.gp, one PNG per
# problem and run.txt (commit, date, machine load); docs/tradeoff.md reads them.
#
#   bench/tradeoff/run.sh [BUILD_DIR] [SWEEP]
#
# SWEEP (optional, e.g. precision): only that sweep's series, into docs/tradeoff/SWEEP/ (same
# files); the full study in docs/tradeoff/ is left as it is.
# BUILD_DIR defaults to ./build (a Release build: cmake -S . -B build -DCMAKE_BUILD_TYPE=Release).
# Two processes run side by side, one thread each, on two halves of the problems; the cost of a
# run is its own process CPU time, so the other process does not count in it. Their CSVs are
# concatenated, then the Pareto flags and the plots are made (run.txt states the wall time).
# Only the plots, from the committed CSV: build/bench/bench_tradeoff --plot-only --out-dir docs/tradeoff
# One problem into another directory:     build/bench/bench_tradeoff --problem wave --out-dir /tmp/t
set -eu
src=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-"$src/build"}
sweep=${2:-}
if [ ! -f "$build/CMakeCache.txt" ]; then
  echo "run.sh: '$build' is not a CMake build directory; configure first:" >&2
  echo "  cmake -S '$src' -B '$build' -DCMAKE_BUILD_TYPE=Release" >&2
  exit 2
fi
cmake --build "$build" -j2 --target bench_tradeoff
exe="$build/bench/bench_tradeoff"
out="$src/docs/tradeoff${sweep:+/$sweep}"
only=${sweep:+--sweep $sweep}
mkdir -p "$out"
# Everything is made in a staging directory beside docs/tradeoff and moved in (a rename per file)
# only when the whole study and its plots are done: a failed or interrupted run leaves
# docs/tradeoff as it was.
work=$(mktemp -d)
stage=$(mktemp -d "$src/docs/.tradeoff.XXXXXX")
pid_a= pid_b=
trap 'rm -rf "$work" "$stage"' EXIT
trap 'kill $pid_a $pid_b 2>/dev/null; exit 130' INT TERM
mkdir -p "$work/a" "$work/b"
start="$(date -u +%Y-%m-%dT%H:%M:%SZ), load average $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo '?')"
t0=$(date +%s)
"$exe" --plan full $only --no-plot --out-dir "$work/a" --problem mms --problem hole 2> "$work/a/log" &
pid_a=$!
"$exe" --plan full $only --no-plot --out-dir "$work/b" --problem vq_uniaxial --problem vq_isotropic \
  --problem vq_shear --problem wave 2> "$work/b/log" &
pid_b=$!
status=0
wait $pid_a || status=1
wait $pid_b || status=1
if [ $status -ne 0 ]; then
  tail -n 5 "$work/a/log" "$work/b/log" >&2
  echo "run.sh: the study failed; docs/tradeoff is unchanged" >&2
  exit 1
fi
{ cat "$work/a/tradeoff.csv"; tail -n +2 "$work/b/tradeoff.csv"; } > "$stage/tradeoff.csv"
if ! "$exe" --plot-only --out-dir "$stage"; then
  echo "run.sh: plotting failed; docs/tradeoff is unchanged" >&2
  exit 1
fi
{
  echo "command: bench/tradeoff/run.sh ${sweep:+build $sweep }(bench_tradeoff --plan full $only, two processes of 1 thread)"
  echo "commit: $(git -C "$src" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "start: $start"
  echo "end: $(date -u +%Y-%m-%dT%H:%M:%SZ), load average $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo '?')"
  echo "wall time: $(( $(date +%s) - t0 )) s"
  echo "cpu: $(awk -F, 'NR > 1 { s += $19 } END { printf "%.0f s summed over the runs", s }' "$stage/tradeoff.csv")"
  tail -n 1 "$work/a/log" "$work/b/log" | sed "s#$work#WORK#g"
} > "$stage/run.txt"
for f in "$out"/*.png; do # plots of problems the new study no longer has
  [ -e "$f" ] && [ ! -e "$stage/$(basename "$f")" ] && rm -f "$f"
done
for f in "$stage"/*; do
  mv -f "$f" "$out/"
done
echo "results in $out (tradeoff.csv, *.png, run.txt)"
