#!/usr/bin/env bash
# The whole cross-check with the original (docs/validation.md, "Cross-check with the original"),
# each step resumable: Chrono + PyChrono, the original's code, the original's trials (the task
# lists in scripts/reference/tasks/), vb's trials on the same worlds, the comparison.
#
#   VB_REFERENCE_CACHE=DIR scripts/reference/crosscheck.sh [--out DIR] [--only original|vb|compare]
#
# --out: results directory (default results/reference): original/ (run_original.py), vb_*/
# (run_vb.sh), compare/ (compare.py: report.md, trials.csv, png/). The original's trials take
# ~1 min (PID, rigid) to ~10 min (MPPI, EH) each on two cores; everything runs under nice -n 10.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
cache="${VB_REFERENCE_CACHE:-$HOME/.cache/vb-reference}"
out="results/reference"
only=""
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    --only) only="$2"; shift 2 ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) echo "crosscheck: unknown option $1 (valid: --out DIR, --only original|vb|compare)" >&2; exit 2 ;;
  esac
done
export VB_REFERENCE_CACHE="$cache"
data="$repo/../shared/verti_bench_calibration/envs/data/BenchMaps/sampled_maps"
tasks="$here/tasks"
if [ -z "$only" ] || [ "$only" = original ]; then
  nice -n 10 "$here/build_chrono.sh" --cache "$cache"
  "$here/prepare_original.sh" --cache "$cache" --data "$data"
  nice -n 10 "$here/run_original.py" --tasks "$tasks/sample.txt" "$tasks/core.txt" \
    "$tasks/eh_mppi.txt" --out "$out/original" --trial-timeout 3600
fi
if [ -z "$only" ] || [ "$only" = vb ]; then
  nice -n 10 "$here/run_vb.sh" --data "$data" --out "$out" --systems "pid pid_original eh mppi"
fi
if [ -z "$only" ] || [ "$only" = compare ]; then
  vbs=()
  for d in vb_pid_hmmwv vb_pid_hmmwv_chrono vb_pid_original_hmmwv vb_pid_original_hmmwv_chrono \
           vb_pid_hmmwv_rules-verti_bench vb_eh_hmmwv vb_mppi_hmmwv; do
    [ -d "$out/$d" ] && vbs+=("$out/$d")
  done
  "$cache/venv/bin/python" "$here/compare.py" --original "$out/original" \
    "$repo/../shared/reference/original_pid_runs" --vb "${vbs[@]}" --data "$data" \
    --out "$out/compare"
fi
