#!/bin/sh
# Finite-element reference of the two-hole plate (README.md here): mesh, CalculiX run, damage table.
#   run.sh OUTDIR [HF [H [U_MAX [DU]]]]     static, grip pulled to U_MAX mm (default 1.6) in steps
#                                          of DU mm (default 0.025)
#   DYNAMIC=1 run.sh OUTDIR [HF [H [T_END [DT]]]]  implicit dynamics at 2000 mm/s to T_END s
# HF: element size [mm] around the holes (default 0.5), H elsewhere (default 1.5).
# CENTRES="X1 Y1 X2 Y2": other hole centres [mm] (default 17.5 42.5 32.5 57.5, pdk's scene).
# Needs gmsh, ccx (Debian: apt-get install gmsh calculix-ccx) and python3-numpy; reference only,
# never a dependency of pdk. Threads: OMP_NUM_THREADS (default 2).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out=${1:?usage: run.sh OUTDIR [HF [H [U_MAX|T_END [DU|DT]]]]}
hf=${2:-0.5}; h=${3:-1.5}; arg4=${4:-}; arg5=${5:-}
py=${PYTHON:-/usr/bin/python3}; [ -x "$py" ] || py=python3
for tool in gmsh ccx "$py"; do
  command -v $tool >/dev/null || { echo "run.sh: $tool not found (apt-get install gmsh calculix-ccx python3-numpy)" >&2; exit 1; }
done
set -- ${CENTRES:-17.5 42.5 32.5 57.5}
[ $# = 4 ] || { echo "run.sh: CENTRES needs four numbers, X1 Y1 X2 Y2 [mm]" >&2; exit 1; }
x1=$1; y1=$2; x2=$3; y2=$4
mkdir -p "$out"; cd "$out"
gmsh -2 "$here/plate.geo" -setnumber hf "$hf" -setnumber h "$h" -setnumber x1 "$x1" -setnumber y1 "$y1" \
  -setnumber x2 "$x2" -setnumber y2 "$y2" -format inp -o mesh.inp > gmsh.log 2>&1 ||
  { echo "run.sh: gmsh failed, see $out/gmsh.log" >&2; exit 1; }
if [ "${DYNAMIC:-0}" = 1 ]; then
  end=${arg4:-0.7e-3}; inc=${arg5:-4e-6}; mode="--dynamic $end"; per=2000
else
  end=${arg4:-1.6}; inc=${arg5:-0.025}; mode="--static $end"; per=$end
fi
"$py" "$here/ccx_input.py" mesh.inp job.inp $mode --increment "$inc" --centres $x1 $y1 $x2 $y2
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
export CCX_NPROC_STIFFNESS=$OMP_NUM_THREADS CCX_NPROC_EQUATION_SOLVER=$OMP_NUM_THREADS
rm -f job.dat damage.txt
ccx -i job > ccx.log 2>&1 || { echo "run.sh: ccx failed, see $out/ccx.log and job.sta" >&2; exit 1; }
grep -q "Job finished" ccx.log || { echo "run.sh: ccx did not finish, see $out/ccx.log" >&2; exit 1; }
"$py" "$here/damage.py" job.dat job.inp --u-per-time "$per" --centres $x1 $y1 $x2 $y2 > damage.txt.part
mv damage.txt.part damage.txt
echo "run.sh: $out/damage.txt"
