#!/usr/bin/env bash
# Submits a vb benchmark matrix to Slurm as a job array of N shards (vb_batch --shard i/N) plus a
# merge job that runs after all shards succeeded (vb_report merge, then vb_report).
#
#   usage: tools/slurm/submit.sh [options] -- ENV... [vb_batch matrix flags]
#   options:
#     --shards N        array size (default 4)
#     --out DIR         output directory (required); shard i writes DIR/shard_i, the merge DIR/merged
#                       and the report DIR/merged/report; Slurm logs go to DIR/logs
#     --partition P     Slurm partition (default: the cluster's default partition)
#     --time T          time limit per shard, Slurm syntax (default 02:00:00)
#     --cpus C          CPUs per shard = vb_batch --jobs (default 4)
#     --mem M           memory per shard, Slurm syntax (default 2G; one trial needs ~100 MB)
#     --bin DIR         directory with vb_batch and vb_report (default: build/tools of this tree)
#     --sbatch-args S   extra sbatch arguments for both jobs, e.g. "--account=abc --qos=normal"
#   Prints "array <id> merge <id>". Re-submitting the same command resumes: every shard skips the
#   trials already recorded in its directory (docs/batch.md).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
shards=4 out= partition= time_limit=02:00:00 cpus=4 mem=2G bin="$here/../../build/tools" extra=
while [ $# -gt 0 ]; do
  case "$1" in
    --shards) shards=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --partition) partition=$2; shift 2 ;;
    --time) time_limit=$2; shift 2 ;;
    --cpus) cpus=$2; shift 2 ;;
    --mem) mem=$2; shift 2 ;;
    --bin) bin=$2; shift 2 ;;
    --sbatch-args) extra=$2; shift 2 ;;
    --) shift; break ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "submit.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -n "$out" ] || { echo "submit.sh: --out is required" >&2; exit 2; }
[ $# -gt 0 ] || { echo "submit.sh: no matrix given after --" >&2; exit 2; }
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || { echo "submit.sh: --shards must be a positive integer" >&2; exit 2; }
bin=$(cd "$bin" && pwd)
[ -x "$bin/vb_batch" ] && [ -x "$bin/vb_report" ] || { echo "submit.sh: no vb_batch/vb_report in $bin" >&2; exit 2; }
mkdir -p "$out/logs"
out=$(cd "$out" && pwd)

common=(--parsable --export=ALL,VB_BIN="$bin",VB_OUT="$out",VB_SHARDS="$shards")
[ -n "$partition" ] && common+=(--partition="$partition")
# shellcheck disable=SC2206
[ -n "$extra" ] && common+=($extra)

array_id=$(sbatch "${common[@]}" --job-name=vb_shard --array="0-$((shards - 1))" \
  --cpus-per-task="$cpus" --mem="$mem" --time="$time_limit" \
  --output="$out/logs/shard_%a.out" "$here/vb_shard.sbatch" "$@")
array_id=${array_id%%;*}
merge_id=$(sbatch "${common[@]}" --job-name=vb_merge --dependency="afterok:$array_id" \
  --cpus-per-task=1 --mem=1G --time=00:30:00 --output="$out/logs/merge.out" \
  "$here/vb_merge.sbatch")
merge_id=${merge_id%%;*}
echo "array $array_id merge $merge_id"
