#!/usr/bin/env bash
# ctest parallel_split: tools/slurm/render_parallel.sh renders stage4 on builtin:cornell in 3
# parts through GNU parallel (2 at a time) and merges them; the merge must equal a one-run
# render bit for bit. A second run of the same command keeps the finished parts. Skipped (77)
# where GNU parallel is not installed.
#
# usage: parallel_split_test.sh BIN_DIR EXR_IDENTICAL
set -euo pipefail

me=parallel_split
[ $# -eq 2 ] || { echo "usage: parallel_split_test.sh BIN_DIR EXR_IDENTICAL" >&2; exit 2; }
bin=$(realpath -- "$1")
identical=$(realpath -- "$2")
src=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
command -v parallel >/dev/null || {
  echo "$me: skipped: GNU parallel is not installed; on Debian: sudo apt-get install parallel (.ci/run installs it)"
  exit 77
}
for program in stage4_direct_indirect pt_merge; do
  [ -x "$bin/$program" ] || { echo "$me: FAILED: $bin/$program is not built" >&2; exit 1; }
done
dir=$(mktemp -d "${TMPDIR:-/tmp}/pt-parallel.XXXXXX")
trap 'rm -rf "$dir"' EXIT
fail() { echo "$me: FAILED: $*" >&2; exit 1; }

# The squared-luminance sums of a merge may differ from the one run's in their last bits
# (docs/film.md): film.YY within 1e-14 relative, every other channel bit for bit.
# 80 spp in 3 parts: blocks of 16 samples 0-1, 1-3, 3-5, so the parts hold 16, 32 and 32.
scene=(--backend cpu --scene builtin:cornell --width 24 --height 16 --seed 3)
"$bin/stage4_direct_indirect" "${scene[@]}" --spp 80 --threads 2 --out "$dir/one_run.exr" >/dev/null
split=("$src/tools/slurm/render_parallel.sh" --out "$dir/merged.exr" --spp 80 --parts-count 3
       --jobs 2 --threads 1 --bin "$bin" -- "${scene[@]}")
"${split[@]}" </dev/null >"$dir/first.log" 2>&1 || { cat "$dir/first.log" >&2; fail "render_parallel.sh failed"; }
"$identical" --tolerance film.YY=1e-14 "$dir/one_run.exr" "$dir/merged.exr" || fail "the merge of 3 parallel parts differs from the one-run render"
rm "$dir/merged.exr"
"${split[@]}" </dev/null >"$dir/second.log" 2>&1 || { cat "$dir/second.log" >&2; fail "render_parallel.sh failed the second time"; }
[ "$(grep -c 'is already done' "$dir/second.log")" = 3 ] || { cat "$dir/second.log" >&2; fail "a second run rendered a finished part again"; }
"$identical" --tolerance film.YY=1e-14 "$dir/one_run.exr" "$dir/merged.exr" || fail "the second merge differs from the one-run render"
echo "$me: the merge of 3 parts run by GNU parallel equals the one-run render (bit for bit, the squared-luminance sums to 1e-14)"
