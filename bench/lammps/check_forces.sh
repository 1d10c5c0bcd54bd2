#!/usr/bin/env bash
# Force-for-force check of pdk's pmb and lps against LAMMPS peri/pmb and peri/lps on a small
# randomly displaced lattice (in.peri_forces), then the energy bookkeeping of both codes.
#
#   bench/lammps/check_forces.sh [BUILD_DIR] [L]      (default build, L = 12)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../../build}
L=${2:-12}
check=$build/bench/bench_lammps_check
[ -x "$check" ] || { echo "check_forces.sh: build $check first (cmake --build $build --target bench_lammps_check)" >&2; exit 1; }
command -v lmp >/dev/null || { echo "check_forces.sh: LAMMPS (lmp) not found" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
status=0
for style in pmb lps; do
  lmp -in "$here/in.peri_forces" -var style $style -var L "$L" -var amp 0.02 -log lmp.$style.log >/dev/null
  pe=$(awk '/^PE_LAMMPS/ {print $2}' lmp.$style.log)
  echo "$style: LAMMPS $(grep -m1 'total # of bonds' lmp.$style.log | sed 's/^ *//')"
  "$check" --style $style --ref ref.$style.dump --cur cur.$style.dump --pe "$pe" || status=1
done
exit $status
