#!/usr/bin/env bash
# Batch throughput benchmark: vb_batch with PID + HMMWV over every task in tasks/ (all pairs,
# the benchmark's 60 s limit), REPEATS times each with --jobs 1 and --jobs 2 (or JOBS), fresh
# output directory every run. Reports median wall time, trials per hour, the speed-up over
# serial, and the extrapolated wall time of the full 1000-trial (100 environments x 10 pairs) PID
# evaluation. Trials that end as `error` (e.g. deformable terrain before the soil solver) take
# no time and are excluded from the per-trial rates.
#   usage: scripts/bench_batch.sh [REPEATS] [JOBS]      (defaults 3 and $(nproc))
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
jobs=${2:-$(nproc)}
bin=build/tools/vb_batch
[ -x "$bin" ] || { echo "bench: build first (scripts/build.sh)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {if (NR%2) print a[(NR+1)/2]; else print (a[NR/2]+a[NR/2+1])/2}'; }
load0=$(cut -d' ' -f1-3 /proc/loadavg)
declare -A wall cpu
for j in 1 "$jobs"; do
  for r in $(seq 1 "$repeats"); do
    printf '\rbench: --jobs %s run %d/%d' "$j" "$r" "$repeats" >&2
    # wall, user and system seconds of vb_batch and all its workers
    /usr/bin/time -f '%e %U %S' -o "$out/time" \
      "$bin" tasks/ --vehicles hmmwv --systems pid --jobs "$j" --quiet --out "$out/j${j}_r$r" > /dev/null
    read -r w u s < "$out/time"
    echo "$w" >> "$out/wall_j$j.txt"
    echo "$u + $s" | bc -l >> "$out/cpu_j$j.txt"
  done
  wall[$j]=$(median < "$out/wall_j$j.txt")
  cpu[$j]=$(median < "$out/cpu_j$j.txt")
done
echo >&2
index="$out/j1_r1/index.csv"
total=$(($(wc -l < "$index") - 1))
ran=$(awk -F, 'NR > 1 && $11 != "error" && $11 != "crashed"' "$index" | wc -l)
sim=$(awk -F, 'NR > 1 && $13 != "" {s += $13} END {printf "%.1f", s}' "$index")
echo "vb_batch PID + HMMWV over tasks/ ($(ls tasks/*.yaml | wc -l) tasks, $total trials, $ran ran, " \
     "$sim s simulated), $repeats runs each, $(nproc) cores, host $(hostname), $(date -u +%F)"
echo "load average before: $load0 (the machine may be shared: compare cpu_s with wall_s)"
printf '%-6s %12s %12s %14s %10s %14s\n' jobs median_wall_s median_cpu_s trials_per_h speedup cpu_s_per_trial
for j in 1 "$jobs"; do
  w=${wall[$j]}
  printf '%-6s %12.2f %12.2f %14.0f %10.2f %14.3f\n' "$j" "$w" "${cpu[$j]}" \
    "$(echo "$ran * 3600 / $w" | bc -l)" "$(echo "${wall[1]} / $w" | bc -l)" \
    "$(echo "${cpu[$j]} / $ran" | bc -l)"
done
w=${wall[$jobs]}
printf 'extrapolated 1000-trial PID evaluation, --jobs %s, measured wall: %.1f min (target <= 30 min)\n' \
  "$jobs" "$(echo "1000 * $w / $ran / 60" | bc -l)"
printf 'extrapolated 1000-trial PID evaluation from CPU time on %s idle cores: %.1f min\n' \
  "$jobs" "$(echo "1000 * ${cpu[$jobs]} / $ran / $jobs / 60" | bc -l)"
