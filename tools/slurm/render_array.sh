#!/usr/bin/env bash
# Submits one render to Slurm as a job array of sample ranges, and a second job that merges
# the parts once every task has succeeded (docs/distributed.md).
#
# usage: tools/slurm/render_array.sh --out MERGED.exr --spp N [--tasks T] [--stage NAME]
#          [--bin DIR] [--parts DIR] [--cpus-per-task C] [--checkpoint SECONDS]
#          [--sbatch ARG]... [--parsable] [-- STAGE_OPTIONS...]
#
#   --out MERGED.exr     the merged image (pt_merge writes it)
#   --spp N              samples per pixel of the whole render
#   --tasks T            array tasks, one part each (default 4; at most ceil(N/16))
#   --stage NAME         the stage program (default stage4_direct_indirect)
#   --bin DIR            where the programs are (default: build/bin of this checkout)
#   --parts DIR          where the parts, their checkpoints and the jobs' logs go
#                        (default: MERGED.exr without .exr, plus .parts)
#   --cpus-per-task C    sbatch --cpus-per-task; each part renders on the CPUs it is given
#                        (SLURM_CPUS_ON_NODE)
#   --checkpoint S       seconds between a part's checkpoints (default 60)
#   --sbatch ARG         one more sbatch option for both jobs, e.g. --sbatch --partition=short
#   --parsable           print only "ARRAY_JOB_ID MERGE_JOB_ID"
#   STAGE_OPTIONS        the stage's options (--scene, --width, --seed, --backend, ...)
#
# Task I of the array runs tools/slurm/render_part.sh, which renders its range with
# `--samples FIRST:COUNT` and `--checkpoint`, and resumes its checkpoint when Slurm requeues
# it (the array is submitted with --requeue). The split (render_part.sh's header) falls on
# the render's pass ends, so the merged image equals a one-run render bit for bit. The
# merge job (--dependency=afterok) runs `pt_merge --out MERGED.exr PART.exr...`.
# Submitting the same command again reuses the parts already done and resumes the others.
set -euo pipefail

me=render_array.sh
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
die() { echo "$me: $*" >&2; exit 2; }
# shellcheck source=tools/slurm/split_common.sh
. "$here/split_common.sh"
usage() {
  echo "usage: $me --out MERGED.exr --spp N [--tasks T] [--stage NAME] [--bin DIR] [--parts DIR] [--cpus-per-task C] [--checkpoint SECONDS] [--sbatch ARG]... [--parsable] [-- STAGE_OPTIONS...]" >&2
  exit 2
}

out= spp= tasks=4 stage=stage4_direct_indirect bin=$here/../../build/bin parts= cpus= checkpoint=60
parsable=0 sbatch_args=()
while [ $# -gt 0 ]; do
  case $1 in
    --) shift; break ;;
    --*=*) set -- "${1%%=*}" "${1#*=}" "${@:2}"; continue ;;
    -h|--help) usage ;;
    --parsable) parsable=1; shift ;;
    --out|--spp|--tasks|--stage|--bin|--parts|--cpus-per-task|--checkpoint|--sbatch)
      [ $# -ge 2 ] || die "$1 needs a value"
      case $1 in
        --out) out=$2 ;; --spp) spp=$2 ;; --tasks) tasks=$2 ;; --stage) stage=$2 ;;
        --bin) bin=$2 ;; --parts) parts=$2 ;; --cpus-per-task) cpus=$2 ;;
        --checkpoint) checkpoint=$2 ;; --sbatch) sbatch_args+=("$2") ;;
      esac
      shift 2 ;;
    *) die "unknown option '$1' (stage options go after --)" ;;
  esac
done
[ -n "$out" ] && [ -n "$spp" ] || usage
[[ $out == *.exr ]] || die "--out must name an .exr file (the merge writes EXR), not '$out'"
[[ $tasks =~ ^[0-9]{1,6}$ ]] && [ "$tasks" -ge 1 ] || die "--tasks must be a positive integer, not '$tasks'"
[ -z "$cpus" ] || [[ $cpus =~ ^[0-9]{1,6}$ && $cpus -ge 1 ]] || die "--cpus-per-task must be a positive integer, not '$cpus'"
command -v sbatch >/dev/null || die "sbatch not found: run this on a Slurm login node (or use tools/slurm/render_parallel.sh)"
resolve_split_paths

# The arguments every task gets.
part_args=(--bin "$bin" --stage "$stage" --spp "$spp" --parts "$parts" --count "$tasks"
           --checkpoint "$checkpoint" -- "$@")
list_split_parts "${part_args[@]}"

name=pt-$(basename "${out%.exr}")
array_id=$(sbatch --parsable --job-name="$name" --array="0-$((tasks - 1))" --requeue \
  --open-mode=append --output="$parts/slurm-%A_%a.out" ${cpus:+--cpus-per-task="$cpus"} \
  "${sbatch_args[@]}" "$here/render_part.sh" "${part_args[@]}") ||
  die "sbatch refused the job array (its message is above)"
array_id=${array_id%%;*}
merge_command=$(printf '%q ' exec "$bin/pt_merge" --out "$out" "${part_files[@]}")
merge_id=$(sbatch --parsable --job-name="$name-merge" --dependency="afterok:$array_id" \
  --kill-on-invalid-dep=yes --output="$parts/slurm-merge-%j.out" "${sbatch_args[@]}" \
  --wrap "$merge_command") || {
  scancel "$array_id" || true
  die "sbatch refused the merge job (its message is above); job array $array_id cancelled"
}
merge_id=${merge_id%%;*}

if [ "$parsable" = 1 ]; then
  echo "$array_id $merge_id"
else
  echo "$me: job array $array_id renders $spp spp of $stage in $tasks parts into $parts/"
  echo "$me: job $merge_id merges them into $out once every task has succeeded"
  echo "$me: watch: squeue -j $array_id,$merge_id   logs: $parts/slurm-*.out"
fi
