#!/usr/bin/env bash
# Renders one frame in parts through GNU parallel, on this machine or on a lab of machines
# (--sshlogin), with the same split as the Slurm job array, then merges the parts
# (docs/distributed.md).
#
# usage: tools/slurm/render_parallel.sh --out MERGED.exr --spp N [--parts-count T]
#          [--stage NAME] [--bin DIR] [--parts DIR] [--jobs J] [--threads N]
#          [--checkpoint SECONDS] [--sshlogin LOGINS]... [-- STAGE_OPTIONS...]
#
#   --out MERGED.exr   the merged image
#   --spp N            samples per pixel of the whole render
#   --parts-count T    parts (default 4; at most ceil(N/16))
#   --stage NAME       the stage program (default stage4_direct_indirect)
#   --bin DIR          where the programs are (default: build/bin of this checkout)
#   --parts DIR        where the parts and their checkpoints go (default: MERGED.exr
#                      without .exr, plus .parts)
#   --jobs J           parts at once on each machine (parallel -j; default 1)
#   --threads N        threads of each part (default 0: all cores of its machine)
#   --checkpoint S     seconds between a part's checkpoints (default 60)
#   --sshlogin LOGINS  parallel's --sshlogin, e.g. "lab01,lab02,lab03" or ":" for this
#                      machine too; the machines must see the same paths (a shared home)
#
# Each part is tools/slurm/render_part.sh --index I --count T. When a machine fails, run the
# same command again: finished parts are kept, cut ones resume their checkpoints.
set -euo pipefail

me=render_parallel.sh
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
die() { echo "$me: $*" >&2; exit 2; }
# shellcheck source=tools/slurm/split_common.sh
. "$here/split_common.sh"
usage() {
  echo "usage: $me --out MERGED.exr --spp N [--parts-count T] [--stage NAME] [--bin DIR] [--parts DIR] [--jobs J] [--threads N] [--checkpoint SECONDS] [--sshlogin LOGINS]... [-- STAGE_OPTIONS...]" >&2
  exit 2
}

out= spp= count=4 stage=stage4_direct_indirect bin=$here/../../build/bin parts= jobs=1 threads=0
checkpoint=60 logins=()
while [ $# -gt 0 ]; do
  case $1 in
    --) shift; break ;;
    --*=*) set -- "${1%%=*}" "${1#*=}" "${@:2}"; continue ;;
    -h|--help) usage ;;
    --out|--spp|--parts-count|--stage|--bin|--parts|--jobs|--threads|--checkpoint|--sshlogin)
      [ $# -ge 2 ] || die "$1 needs a value"
      case $1 in
        --out) out=$2 ;; --spp) spp=$2 ;; --parts-count) count=$2 ;; --stage) stage=$2 ;;
        --bin) bin=$2 ;; --parts) parts=$2 ;; --jobs) jobs=$2 ;; --threads) threads=$2 ;;
        --checkpoint) checkpoint=$2 ;; --sshlogin) logins+=(--sshlogin "$2") ;;
      esac
      shift 2 ;;
    *) die "unknown option '$1' (stage options go after --)" ;;
  esac
done
[ -n "$out" ] && [ -n "$spp" ] || usage
[[ $out == *.exr ]] || die "--out must name an .exr file (the merge writes EXR), not '$out'"
[[ $count =~ ^[0-9]{1,6}$ ]] && [ "$count" -ge 1 ] || die "--parts-count must be a positive integer, not '$count'"
[[ $jobs =~ ^[0-9]{1,4}$ ]] && [ "$jobs" -ge 1 ] || die "--jobs must be a positive integer, not '$jobs'"
command -v parallel >/dev/null || die "GNU parallel not found (Debian: sudo apt-get install parallel)"
resolve_split_paths

part_args=(--bin "$bin" --stage "$stage" --spp "$spp" --parts "$parts" --count "$count"
           --threads "$threads" --checkpoint "$checkpoint" -- "$@")
list_split_parts "${part_args[@]}"

# {} is the part's index; parallel quotes every other argument for the shell (and ssh).
# --halt now,fail=1: the first failed part stops the others (they keep their checkpoints).
seq 0 $((count - 1)) | parallel -q --halt now,fail=1 --line-buffer --tag -j "$jobs" "${logins[@]}" \
  "$here/render_part.sh" --index '{}' "${part_args[@]}" ||
  die "a part failed (its message is above); run the same command again to resume"
exec "$bin/pt_merge" --out "$out" "${part_files[@]}"
