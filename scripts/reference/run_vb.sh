#!/usr/bin/env bash
# vb's side of the cross-check with the original (docs/validation.md, "Cross-check with the
# original"): imports original worlds with vb_import and runs vb's PID on all their pairs with
# vb_batch, for the vehicle/rules combinations that the comparison reads. Resumable (vb_batch).
#
#   scripts/reference/run_vb.sh [--data DIR] [--worlds "1 5 ..."] [--out DIR] [--jobs N]
#                               [--systems "pid pid_original"] [--build DIR]
#
# --data: an original sampled_maps directory (default: the calibration worlds beside the repo);
# --worlds: default every world of --data; --out: default results/reference; --systems: vb
# systems to run (e.g. add "eh mppi eh_original mppi_original" for the EH/MPPI subset).
# Writes OUT/vb_tasks/origN.yaml (imported; never committed) and one vb_batch directory per run:
#   OUT/vb_<system>_hmmwv           vb's default HMMWV, vb's rules
#   OUT/vb_<system>_hmmwv_chrono    hmmwv_chrono (the Chrono model's artefacts), vb's rules
#   OUT/vb_pid_hmmwv_rules-verti_bench   vb's PID and HMMWV under the original's rules
# Trajectories every 10 steps (20 Hz), as run_original.py records.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
data="$repo/../shared/verti_bench_calibration/envs/data/BenchMaps/sampled_maps"
out="results/reference"
jobs=2
systems="pid pid_original"
build="$repo/build"
worlds=""
while [ $# -gt 0 ]; do
  case "$1" in
    --data) data="$2"; shift 2 ;;
    --worlds) worlds="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --systems) systems="$2"; shift 2 ;;
    --build) build="$2"; shift 2 ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) echo "run_vb: unknown option $1 (valid: --data, --worlds, --out, --jobs, --systems, --build)" >&2; exit 2 ;;
  esac
done
cfg="$data/Configs/Final"
[ -d "$cfg" ] || { echo "run_vb: $cfg: no such directory (give --data)" >&2; exit 2; }
[ -x "$build/tools/vb_batch" ] || { echo "run_vb: $build/tools/vb_batch missing (build vb first)" >&2; exit 2; }
if [ -z "$worlds" ]; then
  worlds="$(ls "$cfg"/config*_*.yaml | sed -E 's|.*/config([0-9]+)_.*|\1|' | sort -n | tr '\n' ' ')"
fi
mkdir -p "$out/vb_tasks"
tasks=()
for w in $worlds; do
  c=$(ls "$cfg"/config"$w"_*.yaml 2>/dev/null | head -1)
  [ -n "$c" ] || { echo "run_vb: no config for world $w in $cfg" >&2; exit 2; }
  level=$(basename "$c" .yaml | sed -E 's/config[0-9]+_//')
  t="$out/vb_tasks/orig$w.yaml"
  if [ ! -f "$t" ]; then
    "$build/tools/vb_import" --config "$c" --world "$data/Worlds/$w.bmp" \
      --labels "$cfg/labels${w}_$level.npy" --out "$out/vb_tasks" --name "orig$w" > /dev/null
  fi
  tasks+=("$t")
done
run() {  # run NAME SYSTEM VEHICLE RULES
  echo "run_vb: $1 (${#tasks[@]} worlds, all pairs)"
  "$build/tools/vb_batch" "${tasks[@]}" --vehicles "$3" --systems "$2" --rules "$4" \
    --traj-every 10 --jobs "$jobs" --quiet --out "$out/$1"
}
for system in $systems; do
  run "vb_${system}_hmmwv" "$system" hmmwv vb
  run "vb_${system}_hmmwv_chrono" "$system" hmmwv_chrono vb
done
run "vb_pid_hmmwv_rules-verti_bench" pid hmmwv verti_bench
