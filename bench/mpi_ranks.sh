#!/bin/sh
# Time of a force-loop scene on 1 and 2 MPI ranks (docs/scaling.md): an LPS cube (32 000
# particles, delta = 3.015 spacings, 122 bonds each, general path: stencil off) pulled at one
# face, 60 explicit steps; one thread per rank. Prints, per rank count, the median over REPEATS
# of the stepping time `pdk run` reports ("done: ... (X s stepping)"), and the CPU model and load.
# Usage: bench/mpi_ranks.sh BUILD_DIR [REPEATS]   (needs a build with MPI and mpiexec on PATH)
set -eu
build=${1:?usage: bench/mpi_ranks.sh BUILD_DIR [REPEATS]}
repeats=${2:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/cube.yaml" <<'YAML'
name: cube
dimension: 3
geometry:
  lattice: cubic
  spacing: 1.0e-3
  horizon_factor: 3.015
  box: {lo: [0, 0, 0], hi: [0.04, 0.02, 0.04]}
material: {density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.25}
model: {kind: lps, stencil: off}
sets:
  - {name: held, box: {lo: [-1, -1, -1], hi: [0.003, 1, 1]}}
  - {name: pulled, box: {lo: [0.037, -1, -1], hi: [1, 1, 1]}}
boundary_conditions:
  - {set: held, type: displacement, x: 0, y: 0, z: 0}
  - {set: pulled, type: velocity, x: 0.1}
solver: {steps: 60}
output: {history_interval: 60}
YAML
stepping() { # $1: ranks (0: no mpiexec)
  if [ "$1" = 0 ]; then
    PDK_NUM_THREADS=1 "$build/pdk" run "$work/cube.yaml" -o "$work/out" -q 2>&1
  else
    PDK_NUM_THREADS=1 mpiexec --oversubscribe --allow-run-as-root -x PDK_NUM_THREADS -n "$1" \
      "$build/pdk" run "$work/cube.yaml" -o "$work/out$1" -q 2>&1
  fi | sed -n 's/^done: .*(\([0-9.]*\) s stepping).*/\1/p'
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for p in 0 2; do
  times=""
  for r in $(seq "$repeats"); do times="$times $(stepping "$p")"; done
  echo "ranks $([ "$p" = 0 ] && echo 1 || echo "$p"): stepping s, median of $repeats: $(echo $times | tr ' ' '\n' | median)  (all:$times)"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
