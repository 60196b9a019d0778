#!/bin/bash
# The split's cost (issue 22): one render against 4 parts (--samples FIRST:COUNT) plus
# pt_merge, in total CPU time (user + sys of every process, /usr/bin/time), best of
# REPS alternating runs, and the merge checked against the one run (R,G,B bit for bit).
# Usage: bench/split_cost.sh BIN_DIR WORK_DIR LABEL SPP WIDTH HEIGHT REPS [stage options...]
# e.g. bench/split_cost.sh build/bin /tmp/split cornell 256 128 128 3 --scene builtin:cornell
set -u
BIN=$(cd "$1" && pwd) || exit 1; W=$2; LABEL=$3; SPP=$4; WIDTH=$5; HEIGHT=$6; REPS=$7; shift 7
mkdir -p "$W"; cd "$W" || exit 1
Q=$((SPP / 4))
COMMON=(--backend cpu --threads 2 --width "$WIDTH" --height "$HEIGHT" "$@")
cpu() { # command...: prints "user+sys wall", appends the program's last line to $W/log
    /usr/bin/time -o t.txt -f "%U %S %e" "$@" > out.txt 2>&1 || { cat out.txt >&2; exit 1; }
    tail -n 1 out.txt >> log; read -r u s e < t.txt; echo "$(echo "$u + $s" | bc) $e"; }
echo "loadavg before: $(cat /proc/loadavg)"
for rep in $(seq 1 "$REPS"); do
    read -r one one_wall < <(cpu "$BIN/stage4_direct_indirect" "${COMMON[@]}" --samples 0:"$SPP" --out one.exr)
    total=0; wall=0; parts=()
    for k in 0 1 2 3; do
        read -r c e < <(cpu "$BIN/stage4_direct_indirect" "${COMMON[@]}" --samples $((k * Q)):"$Q" --out part$k.exr)
        total=$(echo "$total + $c" | bc); wall=$(echo "$wall + $e" | bc); parts+=("$c")
    done
    read -r m e < <(cpu "$BIN/pt_merge" --out merged.exr part0.exr part1.exr part2.exr part3.exr)
    total=$(echo "$total + $m" | bc); wall=$(echo "$wall + $e" | bc)
    oiiotool one.exr --ch R,G,B -o one_rgb.exr && oiiotool merged.exr --ch R,G,B -o merged_rgb.exr
    if idiff -fail 0 -warn 0 one_rgb.exr merged_rgb.exr > idiff.txt 2>&1; then same=identical; else same=DIFFERENT; fi
    echo "$LABEL rep $rep: one run $one s CPU ($one_wall s wall); parts ${parts[*]} + merge $m = $total s CPU ($wall s wall); ratio $(echo "scale=4; $total / $one" | bc); R,G,B $same"
done
echo "loadavg after: $(cat /proc/loadavg)"
