#!/usr/bin/env bash
# The whole speed-versus-accuracy lab (issue 6): pt_bench's four sections into CSV files
# in docs/results/ (error against time, rays per second, specialised kernels, and rays per
# second against the triangle count with the BVH and Embree, issue 17), then the log-log
# plots and docs/results.md (bench/report.py). Run by `./tutorial bench` after the build;
# about 18 minutes on 2 cores.
# Environment: BUILD_DIR (default build); PT_BENCH_ARGS: more pt_bench options (e.g.
# "--scene cornell --seconds 1" for a quick look).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
OUT=docs/results
mkdir -p "$OUT"
COMMAND="$BUILD_DIR/bin/pt_bench --runs bench/runs.txt --out $OUT --cache $BUILD_DIR/bench_cache ${PT_BENCH_ARGS:-}"
echo "bench: $COMMAND" >&2
# The load of the machine before and after: other jobs on the same cores slow every number.
cut -d' ' -f1-3 /proc/loadavg > "$OUT/load_before.txt"
date -u +%Y-%m-%d > "$OUT/bench_date.txt"
# The machine the numbers are of (bench/report.py prints it; a report made elsewhere keeps it).
echo "$(lscpu | sed -n 's/^Model name: *//p' | head -n 1), $(nproc) cores" > "$OUT/machine.txt"
start=$(date +%s)
# shellcheck disable=SC2086
$COMMAND
cut -d' ' -f1-3 /proc/loadavg > "$OUT/load_after.txt"
echo $(( $(date +%s) - start )) > "$OUT/bench_seconds.txt"
# Debian's python3, which has python3-matplotlib (not one of a version manager).
/usr/bin/python3 bench/report.py --results "$OUT" --command "./tutorial bench" --markdown docs/results.md
[ "${BENCH_CYCLES:-0}" != 1 ] || /usr/bin/python3 bench/cycles/compare.py --bin-dir "$BUILD_DIR/bin"  # issue 23: Cycles side by side (needs blender; docs/results/cycles_notes.md) when BENCH_CYCLES=1
[ "${BENCH_CYCLES:-0}" != 1 ] || /usr/bin/python3 bench/cycles/compare_gltf.py --bin-dir "$BUILD_DIR/bin" --out-dir out/gltf_real --publish docs/results/gltf_real  # issue 46: real glTF files, Cycles through Blender's importer against stage5 (needs blender; 18 min on 2 busy cores)
echo "bench: docs/results.md and the plots in $OUT/" >&2
