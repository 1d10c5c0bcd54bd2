#!/bin/sh
# Two pdk builds, the same answers: runs every shipped scene (or the ones given) with both and
# compares their output files bit for bit.
#
#   tests/compare_builds.sh [-q] [-r] [-t THREADS] OLD_PDK NEW_PDK [SCENE ...]
#
# For each scene both programs run `pdk run SCENE -o DIR --threads THREADS -q` into scratch
# folders; then the history CSV, the field snapshot CSV and the XDMF must be byte-identical
# (cmp), the .h5 files must hold the same objects with the same attributes and dataset bytes
# (h5diff; its exit status is 0 only when nothing differs), and the messages on stderr must be the
# same once the wall times, rates and peak memory of the summary are masked. The .h5's provenance attributes
# (pdk_version, build_type, build_flags, compiler) are compared too: build both programs with the
# same compiler and flags. Refactors that must not change results are checked with this; so is a
# kernel rewrite meant to be bitwise equal.
#
# -q (quick): explicit scenes with an end_time run to a quarter of it, so the check takes minutes
# instead of a quarter of an hour on 2 cores (the ductile plates then stop before their bonds
# break: run without -q for those paths). Default THREADS: 2. Exit 0 when every scene matches,
# 1 when one differs (the differing files are listed), 2 on a usage error.
#
# -r (restart): each explicit scene with an end_time runs in two legs instead, to half its end
# and then continued with --restart from that leg's checkpoint to the end in the same folder, so
# the checkpoint's save and load and the appended outputs are compared too. Needs h5diff (Debian:
# hdf5-tools).
set -eu
quick=0
restart=0
threads=2
usage="usage: $0 [-q] [-r] [-t THREADS] OLD_PDK NEW_PDK [SCENE ...]"
while getopts qrt: opt; do
  case $opt in
  q) quick=1 ;;
  r) restart=1 ;;
  t) threads=$OPTARG ;;
  *) echo "$usage" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
[ $# -ge 2 ] || { echo "$usage" >&2; exit 2; }
old=$1
new=$2
shift 2
for b in "$old" "$new"; do
  [ -x "$b" ] || { echo "$0: $b is not an executable pdk" >&2; exit 2; }
done
command -v h5diff > /dev/null || { echo "$0: needs h5diff (apt-get install hdf5-tools)" >&2; exit 2; }
top=$(cd "$(dirname "$0")/.." && pwd)
[ $# -gt 0 ] || set -- "$top"/scenes/*.yaml

work=$(mktemp -d "${TMPDIR:-/tmp}/compare_builds.XXXXXX")
trap 'rm -rf "$work"' EXIT
bad=0
for scene in "$@"; do
  [ -r "$scene" ] || { echo "$0: cannot read the scene $scene" >&2; exit 2; }
  stem=$(basename "$scene" .yaml)
  # the scene's solver.end_time (block or flow style) and its name (the checkpoint's stem)
  end=$(sed -n 's/^.*end_time: *\([0-9.eE+-]*\).*$/\1/p' "$scene" | head -1)
  name=$(sed -n 's/^name: *\([^ #]*\).*$/\1/p' "$scene" | head -1)
  [ -n "$name" ] || name=$stem
  set --
  if [ $quick = 1 ] && [ -n "$end" ]; then
    end=$(awk -v e="$end" 'BEGIN { printf "%.6g", e / 4 }')
    set -- --set "solver.end_time=$end"
  fi
  legs=1
  [ $restart = 1 ] && [ -n "$end" ] && legs=2
  for side in old new; do
    prog=$old
    [ $side = new ] && prog=$new
    rc=0
    if [ $legs = 2 ]; then
      half=$(awk -v e="$end" 'BEGIN { printf "%.6g", e / 2 }')
      "$prog" run "$scene" -o "$work/$side/$stem" --threads "$threads" -q \
        --set "solver.end_time=$half" > "$work/$side.$stem.log" 2>&1 || rc=$?
      [ $rc != 0 ] || "$prog" run "$scene" -o "$work/$side/$stem" --threads "$threads" -q "$@" \
        --restart "$work/$side/$stem/${name}_checkpoint.h5" >> "$work/$side.$stem.log" 2>&1 || rc=$?
    else
      "$prog" run "$scene" -o "$work/$side/$stem" --threads "$threads" -q "$@" \
        > "$work/$side.$stem.log" 2>&1 || rc=$?
    fi
    if [ $rc != 0 ]; then
      echo "$stem: the $side program failed:" >&2
      cat "$work/$side.$stem.log" >&2
      bad=1
      continue 2
    fi
    # the summary's wall times, rates and memory differ from run to run; so do the folders
    sed -e 's/[0-9.][0-9.e+-]* s\b/T s/g' -e 's/[0-9.][0-9.e+-]* bond updates\/s/R bond updates\/s/' \
      -e 's/[0-9.][0-9.]* MiB/M MiB/g' -e "s|$work/$side/|DIR/|g" "$work/$side.$stem.log" \
      > "$work/$side.$stem.masked"
  done
  diffs=""
  for f in "$work/new/$stem"/*; do
    name=$(basename "$f")
    case $name in
    *.png | *.gp) continue ;; # drawn by gnuplot from the CSVs compared here
    esac
    o="$work/old/$stem/$name"
    if [ ! -e "$o" ]; then
      diffs="$diffs $name(only-new)"
    elif [ "${name%.h5}" != "$name" ]; then
      h5diff -q "$o" "$f" > /dev/null 2>&1 || diffs="$diffs $name"
    else
      cmp -s "$o" "$f" || diffs="$diffs $name"
    fi
  done
  for o in "$work/old/$stem"/*; do
    [ -e "$work/new/$stem/$(basename "$o")" ] || diffs="$diffs $(basename "$o")(only-old)"
  done
  cmp -s "$work/old.$stem.masked" "$work/new.$stem.masked" || diffs="$diffs stderr"
  n=$(ls "$work/new/$stem" | wc -l)
  if [ -n "$diffs" ]; then
    echo "$stem: DIFFERENT:$diffs"
    bad=1
  else
    echo "$stem: identical ($n files${1:+, $2}$([ $legs = 2 ] && echo ', two legs'))"
  fi
done
exit $bad
