#!/bin/sh
# Regenerates the tables of docs/validation/queiruga.md (Queiruga & Moridis 2017, V-Q3-V-Q8).
# Usage: bench/run_vq_study.sh [build dir, default build] [output dir, default build/vq_study]
# Each table goes to <out>/<table>.md (progress lines on <out>/<table>.log); the NP lists are the
# ones quoted in docs/validation/queiruga.md. Threads: PDK_VQ_THREADS (default 1 per table; the
# tables run three at a time).
set -e
B=${1:-build}
O=${2:-$B/vq_study}
T=${PDK_VQ_THREADS:-1}
S=$B/bench/study_vq
mkdir -p "$O"
run() { name=$1; shift; "$S" "$@" --threads "$T" > "$O/$name.md" 2> "$O/$name.log"; }
( run table3 table3 --np 100,140,200 && run table4 table4 --np 70,100,140 ) &
( run vq7 vq7 --np 199 && run vq7_silling one silling shear 4 3.5 99 &&
  run vq7_oterkus one oterkus shear 4 3.5 99 && run table7 table7 --np 200 &&
  run table8f table8f --np 24,50,76,100,124,150,176,200,224,250,276,300,324,350,376,400,424,450,476,500,524 &&
  run table8 table8 --np 24,50,76,100,124,150,176,200,224,250,276,300,324,350,376 ) &
( run table5 table5 --np 70,100,140 ) &
wait
cat "$O"/table3.md "$O"/table4.md "$O"/table5.md "$O"/vq7.md "$O"/vq7_silling.md \
  "$O"/vq7_oterkus.md "$O"/table7.md "$O"/table8f.md "$O"/table8.md
