#!/usr/bin/env bash
# Speed benchmark of whole trials: runs vb_run on TASK (all pairs) REPEATS times and reports, per
# pair and overall, the median real-time factor (simulated s / wall s, setup included) from the
# trial JSON files. Run on an otherwise idle machine; one trial runs on one core.
#   usage: scripts/bench_vb_run.sh [TASK] [REPEATS] [VEHICLE]
set -euo pipefail
cd "$(dirname "$0")/.."
task=${1:-tasks/env042.yaml}
repeats=${2:-5}
vehicle=${3:-hmmwv}
bin=build/tools/vb_run
[ -x "$bin" ] || { echo "bench: build first (scripts/build.sh)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

for r in $(seq 1 "$repeats"); do
  printf '\rbench: run %d/%d' "$r" "$repeats" >&2
  "$bin" "$task" --vehicle "$vehicle" --quiet --out "$out/run$r" > /dev/null
done
echo >&2

# pair, status, sim time, rtf for every trial file
for f in "$out"/run*/*.json; do
  field() { grep -m1 "\"$1\"" "$f" | cut -d: -f2 | tr -d ' ,"'; }
  pair=$(field pair)
  status=$(field status)
  sim=$(field sim_time_s)
  rtf=$(field real_time_factor)
  echo "$pair $status $sim $rtf"
done | sort -n -k1,1 -k4,4g > "$out/all.txt"

median() { sort -g | awk '{a[NR]=$1} END {if (NR%2) print a[(NR+1)/2]; else print (a[NR/2]+a[NR/2+1])/2}'; }
echo "task $task, vehicle $vehicle, system pid, $repeats runs, $(nproc) cores, host $(hostname)"
printf '%-5s %-8s %8s %12s\n' pair status sim_s median_rtf
for p in $(cut -d' ' -f1 "$out/all.txt" | sort -nu); do
  status=$(awk -v p="$p" '$1==p {print $2; exit}' "$out/all.txt")
  sim=$(awk -v p="$p" '$1==p {print $3; exit}' "$out/all.txt")
  rtf=$(awk -v p="$p" '$1==p {print $4}' "$out/all.txt" | median)
  printf '%-5s %-8s %8.2f %12.1f\n' "$p" "$status" "$sim" "$rtf"
done
printf 'all   median rtf over %d trials: %.1f\n' "$(wc -l < "$out/all.txt")" \
  "$(cut -d' ' -f4 "$out/all.txt" | median)"
