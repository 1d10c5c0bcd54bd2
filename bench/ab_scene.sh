#!/bin/sh
# Two pdk builds side by side on one scene: the CPU time of whole runs, alternated.
#
#   bench/ab_scene.sh [-r ROUNDS] [-t THREADS] OLD_PDK NEW_PDK SCENE [--set KEY=VALUE ...]
#
# Each round runs OLD then NEW (NEW then OLD on even rounds, so a drift of the host over a round
# falls on both), `pdk run SCENE --threads THREADS -q` into a scratch folder, and records the
# process's user + system CPU seconds (GNU time). Prints every run, then per build the median,
# and the median of the per-round ratios NEW / OLD: on a shared machine the wall time includes
# other processes' turns, and the absolute times drift by tens of percent between rounds, so the
# ratio within a round is the number to quote. Also compares the two runs' history CSVs (byte
# for byte, or the largest relative difference of the reaction forces) so a speed-up that changed
# the answer shows. Defaults: 3 rounds (an odd number gives a true median), 1 thread.
set -eu
rounds=3
threads=1
while getopts r:t: opt; do
  case $opt in
  r) rounds=$OPTARG ;;
  t) threads=$OPTARG ;;
  *) echo "usage: $0 [-r ROUNDS] [-t THREADS] OLD_PDK NEW_PDK SCENE [--set KEY=VALUE ...]" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
if [ $# -lt 3 ]; then
  echo "usage: $0 [-r ROUNDS] [-t THREADS] OLD_PDK NEW_PDK SCENE [--set KEY=VALUE ...]" >&2
  exit 2
fi
old=$1
new=$2
scene=$3
shift 3
[ -x /usr/bin/time ] || { echo "$0: needs GNU time (/usr/bin/time; apt-get install time)" >&2; exit 2; }
for b in "$old" "$new"; do
  [ -x "$b" ] || { echo "$0: $b is not an executable pdk" >&2; exit 2; }
done
[ -r "$scene" ] || { echo "$0: cannot read the scene $scene" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/ab_scene.XXXXXX")
trap 'rm -rf "$work"' EXIT
log=$work/times
run_one() { # label binary round [--set KEY=VALUE ...]
  label=$1
  bin=$2
  rnd=$3
  shift 3
  if ! /usr/bin/time -f "$rnd $label %U %S" -a -o "$log" "$bin" run "$scene" -o "$work/$label" \
    --threads "$threads" -q "$@" >"$work/$label.log" 2>&1; then
    echo "$0: the $label build failed on $scene (round $rnd):" >&2
    tail -5 "$work/$label.log" >&2
    exit 1
  fi
}
run_pair() {
  r=$1
  shift
  if [ $((r % 2)) -eq 1 ]; then
    run_one old "$old" "$r" "$@"
    run_one new "$new" "$r" "$@"
  else
    run_one new "$new" "$r" "$@"
    run_one old "$old" "$r" "$@"
  fi
}
r=1
while [ "$r" -le "$rounds" ]; do
  run_pair "$r" "$@"
  r=$((r + 1))
done

echo "scene $scene, $threads thread(s), $rounds rounds; CPU seconds (user + system)"
awk '{ cpu[$1 " " $2] = $3 + $4; printf "round %s %s %.2f\n", $1, $2, $3 + $4 }
     END {
       n = 0
       for (k in cpu) { split(k, a, " "); if (a[2] == "old") { n++; o[n] = cpu[k]; nw[n] = cpu[a[1] " new"]; q[n] = nw[n] / o[n] } }
       # medians (insertion sort; n is small)
       for (i = 2; i <= n; i++) for (j = i; j > 1; j--) {
         if (o[j] < o[j-1]) { t = o[j]; o[j] = o[j-1]; o[j-1] = t }
         if (nw[j] < nw[j-1]) { t = nw[j]; nw[j] = nw[j-1]; nw[j-1] = t }
         if (q[j] < q[j-1]) { t = q[j]; q[j] = q[j-1]; q[j-1] = t } }
       m = int((n + 1) / 2)
       printf "median old %.2f s, new %.2f s; median of the per-round ratios new/old %.3f (min %.3f, max %.3f)\n", o[m], nw[m], q[m], q[1], q[n]
     }' "$log"
h_old=$(ls "$work"/old/*_history.csv 2>/dev/null | head -1)
h_new=$(ls "$work"/new/*_history.csv 2>/dev/null | head -1)
if [ -n "$h_old" ] && [ -n "$h_new" ]; then
  if cmp -s "$h_old" "$h_new"; then
    echo "history CSVs: identical"
  else
    awk -F, 'NR == FNR { if (FNR > 1) for (i = 1; i <= NF; i++) a[FNR, i] = $i; else for (i = 1; i <= NF; i++) if ($i ~ /^reaction/) col[i] = 1; next }
             FNR > 1 { for (i in col) { d = $i - a[FNR, i]; if (d < 0) d = -d; s = a[FNR, i] < 0 ? -a[FNR, i] : a[FNR, i]; if (s > big) big = s; if (d > dd) dd = d } }
             END { printf "history CSVs differ: largest reaction-force difference %.3g of the largest reaction (any column)\n", (big > 0 ? dd / big : dd) }' \
      "$h_old" "$h_new"
  fi
fi
