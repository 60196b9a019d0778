#!/usr/bin/env bash
# One part of a render split into sample ranges: the body of each Slurm array task
# (render_array.sh) and of each GNU parallel job (render_parallel.sh); docs/distributed.md.
#
# usage: render_part.sh --bin DIR --spp N --parts DIR [--stage NAME] [--index I --count T]
#                       [--threads N] [--checkpoint SECONDS] [--list] [-- STAGE_OPTIONS...]
#
# --list checks the arguments and prints the T parts' file names, one a line, and renders
# nothing (the submitting scripts use it). The stage options must not set what the split
# sets: --out, --spp, --samples, --threads, --checkpoint, --resume, --time-budget and
# --target-error (a part that stops early would leave a gap).
#
# Part I of T renders the samples this script's split gives it (below), with
# `--samples FIRST:COUNT`, into DIR/part<I>of<T>_samples_<FIRST>-<LAST>.exr, and saves a
# checkpoint beside it every SECONDS (default 60) and when Slurm stops it (SIGTERM). Run
# again (a requeued task, or the same command once more), it resumes that checkpoint, or
# leaves a finished part alone (a part whose checkpoint is gone is finished: the stage
# deletes the checkpoint when the part reaches its last sample).
#
# I and T default to SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT; the threads to
# SLURM_CPUS_ON_NODE (the CPUs Slurm gave this task on its node), else 0 (all cores).
#
# The split: the samples 0 ... N-1 are cut into blocks of 16 (the render's pass size; the
# last block may be shorter), and part I of T gets blocks floor(I*B/T) ... floor((I+1)*B/T)-1
# of the B = ceil(N/16) blocks. Every part therefore starts and ends on a multiple of 16 or
# at N, which are pass ends of the one-run render (its passes end at 1, 2, 4, 8, 16 and
# every multiple of 16), so the parts add the one run's passes and pt_merge gives that run
# bit for bit. T may be at most B.
set -euo pipefail

me=render_part.sh
die() { echo "$me: $*" >&2; exit 2; }
usage() {
  echo "usage: $me --bin DIR --spp N --parts DIR [--stage NAME] [--index I --count T] [--threads N] [--checkpoint SECONDS] [--list] [-- STAGE_OPTIONS...]" >&2
  exit 2
}
is_count() { [[ $1 =~ ^[0-9]+$ ]] && [ "${#1}" -le 10 ]; }

# [excerpt part_range]
# Prints "FIRST COUNT" of part I of T of N samples (the split above).
part_range() {
  local i=$1 t=$2 n=$3 blocks lo hi first end
  blocks=$(( (n + 15) / 16 ))
  lo=$(( i * blocks / t )); hi=$(( (i + 1) * blocks / t ))
  first=$(( 16 * lo )); end=$(( 16 * hi )); [ "$end" -le "$n" ] || end=$n
  echo "$first $(( end - first ))"
}
# [/excerpt]

bin= spp= parts= stage=stage4_direct_indirect
index=${SLURM_ARRAY_TASK_ID:-} count=${SLURM_ARRAY_TASK_COUNT:-}
threads=${SLURM_CPUS_ON_NODE:-0} checkpoint=60 list=0
while [ $# -gt 0 ]; do
  case $1 in
    --) shift; break ;;
    --*=*) set -- "${1%%=*}" "${1#*=}" "${@:2}"; continue ;;
    -h|--help) usage ;;
    --list) list=1; shift ;;
    --bin|--spp|--parts|--stage|--index|--count|--threads|--checkpoint)
      [ $# -ge 2 ] || die "$1 needs a value"
      case $1 in
        --bin) bin=$2 ;; --spp) spp=$2 ;; --parts) parts=$2 ;; --stage) stage=$2 ;;
        --index) index=$2 ;; --count) count=$2 ;; --threads) threads=$2 ;;
        --checkpoint) checkpoint=$2 ;;
      esac
      shift 2 ;;
    *) die "unknown option '$1' (stage options go after --)" ;;
  esac
done
[ -n "$bin" ] && [ -n "$spp" ] && [ -n "$parts" ] || usage
[ "$list" = 1 ] && index=0
[ -n "$index" ] && [ -n "$count" ] ||
  die "no part index: give --index I --count T, or run as a task of a Slurm job array"
is_count "$spp" && [ "$spp" -ge 1 ] || die "--spp must be a positive integer, not '$spp'"
is_count "$count" && [ "$count" -ge 1 ] || die "the part count must be a positive integer, not '$count'"
is_count "$index" && [ "$index" -lt "$count" ] ||
  die "part index '$index' is not one of 0 ... $((count - 1)) (a Slurm array must be --array=0-$((count - 1)))"
is_count "$threads" || die "--threads must be a non-negative integer, not '$threads'"
[[ $checkpoint =~ ^[0-9]*\.?[0-9]+$ && ! $checkpoint =~ ^[0.]+$ ]] ||
  die "--checkpoint must be a positive number of seconds, not '$checkpoint'"
[ "$count" -le $(( (spp + 15) / 16 )) ] ||
  die "$spp spp make only $(( (spp + 15) / 16 )) blocks of 16 samples: use at most that many parts, not $count"
[ -x "$bin/$stage" ] || die "no program $bin/$stage (build it, or give --bin and --stage)"
for a in "$@"; do
  case ${a%%=*} in
    --out|--spp|--samples|--threads|--checkpoint|--resume|--time-budget|--target-error|--help)
      die "the stage option ${a%%=*} is set by the split: leave it out (give --spp and --checkpoint to the script; a part's threads are the CPUs it gets)" ;;
  esac
done

# The part file of part $1 (its range in its name: a later split of other ranges never
# takes it for its own).
part_file() {
  local first n
  read -r first n < <(part_range "$1" "$count" "$spp")
  printf '%s/part%03dof%03d_samples_%d-%d.exr\n' "$parts" "$1" "$count" "$first" $((first + n - 1))
}
if [ "$list" = 1 ]; then
  for ((i = 0; i < count; i++)); do part_file "$i"; done
  exit 0
fi

read -r first n < <(part_range "$index" "$count" "$spp")
mkdir -p "$parts"
out=$(part_file "$index")
ckpt=$out.ckpt
resume=()
if [ -e "$ckpt" ]; then
  echo "$me: part $index of $count resumes $ckpt (restart ${SLURM_RESTART_COUNT:-0})" >&2
  resume=(--resume "$ckpt")
elif [ -e "$out" ]; then
  echo "$me: part $index of $count is already done: $out" >&2
  exit 0
else
  echo "$me: part $index of $count renders samples $first ... $((first + n - 1)) of $spp into $out" >&2
fi
# exec: Slurm's SIGTERM (preemption, scancel, requeue) reaches the stage itself, which
# finishes its pass, saves the checkpoint and the image of the samples done, and exits 143.
exec "$bin/$stage" "$@" --samples "$first:$n" --threads "$threads" --checkpoint "$checkpoint" \
  --out "$out" "${resume[@]}"
