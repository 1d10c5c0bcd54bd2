#!/usr/bin/env bash
# pdk vs LAMMPS PERI side by side (V-PERF): the same free simple-cubic cube (L^3 particles,
# delta = 3.015 dx, partial volumes on, no breakage), the same number of velocity-Verlet steps from
# rest, LAMMPS with `mpirun -np 1` and `-np 2`, pdk (bench_forces --steps) with 1 and 2 threads.
# Prints the time per step of both, the LAMMPS Pair share, ns per directed bond per core, and the
# speed ratio (LAMMPS time / pdk time).
#
#   bench/lammps/run_bench.sh [-b BUILD_DIR] [-s "46 100"] [-n STEPS] [-m "pmb lps"] [-r "1 2"]
#                             [-l csr|sell|stencil]
#
# -s: cube sides (46 -> 97 336 particles, 100 -> 10^6; the 10^6 LAMMPS runs take minutes);
# -n: steps per run (default 10); BUILD_DIR defaults to build-native (configure it with
# -DPDK_NATIVE=ON, see bench/README.md "Force loops"); -l: pdk's layout (bench_forces --layout,
# default csr). Logs stay in $PDK_BENCH_LOGS if set.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$here/../../build-native
sides="46 100"
steps=10
styles="pmb lps"
ranks="1 2"
layout=csr
while getopts "b:s:n:m:r:l:" opt; do
  case $opt in
    b) build=$OPTARG ;;
    s) sides=$OPTARG ;;
    n) steps=$OPTARG ;;
    m) styles=$OPTARG ;;
    r) ranks=$OPTARG ;;
    l) layout=$OPTARG ;;
    *) sed -n 2,14p "$0"; exit 2 ;;
  esac
done
bench=$build/bench/bench_forces
[ -x "$bench" ] || { echo "run_bench.sh: build $bench first" >&2; exit 1; }
command -v lmp >/dev/null || { echo "run_bench.sh: LAMMPS (lmp) not found" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=${PDK_BENCH_LOGS:-$(mktemp -d)}
mkdir -p "$work"
cd "$work"

echo "# pdk vs LAMMPS $(lmp -h | awk '/^Large-scale/ {print $(NF-5), $(NF-4), $(NF-3), $(NF-2), $(NF-1), $NF; exit}'), $steps steps from rest, $(date -u +%Y-%m-%dT%H:%MZ)"
src=$(awk -F= '/^CMAKE_HOME_DIRECTORY/ {print $2}' "$build/CMakeCache.txt" 2>/dev/null || true)
commit=$(git -C "${src:-$here}" rev-parse --short HEAD 2>/dev/null || echo '?')
git -C "${src:-$here}" diff --quiet HEAD 2>/dev/null || commit="$commit+local changes"
echo "# pdk: source ${src:-?} at $commit, $bench, layout $layout"
printf "# %-5s %8s %10s %3s %11s %11s %11s %9s %9s %8s\n" style n bonds P lmp_s/step lmp_pair_s pdk_s/step \
  lmp_ns/b/c pdk_ns/b/c lmp/pdk
for L in $sides; do
  for style in $styles; do
    # pdk first: one process runs every thread count on the same families
    thr_args=""
    for p in $ranks; do thr_args="$thr_args --threads $p"; done
    "$bench" --side "$L" --model "$style" --layout "$layout" $thr_args --steps "$steps" --triad-mib 64 > pdk.$style.$L.txt
    for p in $ranks; do
      log=lmp.$style.$L.np$p.log
      mpirun -np "$p" lmp -in "$here/in.peri_bench" -var style "$style" -var L "$L" -var steps "$steps" \
        -log "$log" -screen none
      loop=$(awk '/^Loop time of/ {print $4}' "$log")
      pair=$(awk '/^Pair / {print $5}' "$log")
      natoms=$(awk '/^Loop time of/ {print $NF=="atoms" ? $(NF-1) : $12}' "$log")
      lbonds=$(awk '/total # of bonds/ {print $NF; exit}' "$log")
      # bench_forces' columns by their header names (model, n, bonds, thr, s/step)
      read -r pn pbonds pstep < <(awk -v p="$p" -v s="$style" '
        /^# model/ {for (k = 2; k <= NF; ++k) col[$k] = k - 1; next}
        /^#/ {next}
        $col["model"] == s && $col["thr"] == p {print $col["n"], $col["bonds"], $col["s/step"]}' pdk.$style.$L.txt)
      [ "$pn" = "$natoms" ] || echo "# warning: particle counts differ: LAMMPS $natoms, pdk $pn"
      [ "$pbonds" = "$lbonds" ] || echo "# warning: bond counts differ: LAMMPS $lbonds, pdk $pbonds"
      awk -v s="$style" -v n="$pn" -v b="$pbonds" -v p="$p" -v loop="$loop" -v pair="$pair" -v steps="$steps" \
          -v pdk="$pstep" 'BEGIN {
            ls = loop / steps; lp = pair / steps;
            printf "  %-5s %8d %10d %3d %11.4f %11.4f %11.4f %9.2f %9.2f %8.2f\n", s, n, b, p, ls, lp, pdk,
                   ls * p / b * 1e9, pdk * p / b * 1e9, ls / pdk }'
    done
  done
done
