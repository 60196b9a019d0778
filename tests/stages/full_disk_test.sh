#!/usr/bin/env bash
# A full disk (docs/reliability.md): every file the programs write (a stage's .png, .exr and
# .hdr, --error-map, pt_compare's --zmap, pt_merge's merged part, a checkpoint) goes to a small
# tmpfs that is full, then almost full (4 KB left, less than any of the files: stage2's noise
# does not compress), over an old file of the same name. Each
# must end with exit 5 and one line naming the disk's error (a checkpoint: one warning, and
# the render goes on), and leave the old file byte for byte as it was, with no temporary file.
# The tmpfs (16 MB) lives in a private mount namespace (unshare: as root, or in a user namespace);
# where neither is allowed the test is skipped (exit 77). Not part of the article.
# usage: full_disk_test.sh BIN_DIR
set -u
bin=$1

if [ "${PT_FULL_DISK_INNER:-}" != 1 ]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  small=(--backend cpu --threads 2 --width 384 --height 288)
  # The old files, and the inputs of pt_compare and pt_merge, made where there is room.
  for ext in png exr hdr; do
    "$bin/stage2_montecarlo" "${small[@]}" --spp 2 --out "$work/old.$ext" >/dev/null || exit 1
  done
  "$bin/stage2_montecarlo" "${small[@]}" --samples 0:16 --out "$work/part0.exr" >/dev/null || exit 1
  "$bin/stage2_montecarlo" "${small[@]}" --samples 16:16 --out "$work/part1.exr" >/dev/null || exit 1
  "$bin/stage1_raycast" "${small[@]}" --spp 4000000 --time-budget 0.3 --checkpoint 0.01 \
    --out "$work/saved.exr" >/dev/null || exit 1
  cp "$work/saved.exr.ckpt" "$work/old.ckpt"
  for ns in "unshare --mount" "unshare --user --map-root-user --mount"; do
    if $ns true 2>/dev/null; then
      PT_FULL_DISK_INNER=1 WORK=$work $ns bash "$0" "$bin"
      exit $?
    fi
  done
  echo "full_disk_test: skipped: no private mount namespace here (unshare refused)"
  exit 77
fi

disk=$WORK/disk
mkdir -p "$disk"
mount -t tmpfs -o size=16m tmpfs "$disk" || { echo "full_disk_test: skipped: cannot mount a tmpfs"; exit 77; }
small=(--backend cpu --threads 2 --width 384 --height 288)
failures=0 cases=0

# Fills the disk: all of it (full) or all but 4 KB (almost).
fill() {
  rm -f "$disk/fill"
  dd if=/dev/zero of="$disk/fill" bs=4k 2>/dev/null
  if [ "$1" = almost ]; then truncate -s -4096 "$disk/fill"; fi
}

# check MODE EXPECTED_EXIT WORDS TARGET_NAME OLD_FILE COMMAND...: the command's exit code and
# stderr, the old file kept, nothing else left on the disk.
check() {
  local mode=$1 expected=$2 words=$3 name=$4 old=$5
  shift 5
  cases=$((cases + 1))
  rm -rf "${disk:?}"/* "$disk"/.[!.]* 2>/dev/null
  cp "$old" "$disk/$name"
  fill "$mode"
  local err rc
  err=$("$@" 2>&1 >/dev/null)
  rc=$?
  local why=""
  [ "$rc" = "$expected" ] || why+=" exit $rc, not $expected;"
  [ "$(printf '%s\n' "$err" | grep -c .)" = 1 ] || why+=" stderr is not one line;"
  case "$err" in *"$words"*) ;; *) why+=" stderr lacks '$words';" ;; esac
  cmp -s "$old" "$disk/$name" || why+=" the old $name changed;"
  local left
  left=$(ls -A "$disk" | grep -v -x -e fill -e "$name")
  [ -z "$left" ] || why+=" left behind: $left;"
  if [ -n "$why" ]; then
    failures=$((failures + 1))
    echo "FAIL ($mode disk) $*:$why"
    echo "  stderr: $err"
  else
    echo "ok   ($mode disk) $name: $err"
  fi
}

nospace="No space left on device"
for mode in full almost; do
  for ext in png exr hdr; do
    check $mode 5 "$nospace" "old.$ext" "$WORK/old.$ext" \
      "$bin/stage2_montecarlo" "${small[@]}" --spp 4 --out "$disk/old.$ext"
  done
  check $mode 5 "$nospace" map.png "$WORK/old.png" \
    "$bin/stage2_montecarlo" "${small[@]}" --spp 4 --out "$WORK/image.exr" --error-map "$disk/map.png"
  check $mode 5 "$nospace" z.png "$WORK/old.png" \
    "$bin/pt_compare" --zmap "$disk/z.png" "$WORK/part0.exr" "$WORK/part1.exr"
  check $mode 5 "$nospace" merged.exr "$WORK/old.exr" \
    "$bin/pt_merge" --out "$disk/merged.exr" "$WORK/part0.exr" "$WORK/part1.exr"
  # A checkpoint that cannot be saved is said once; the render goes on and ends well.
  check $mode 0 "cannot write checkpoint '$disk/saved.ckpt': $nospace" saved.ckpt "$WORK/old.ckpt" \
    "$bin/stage1_raycast" "${small[@]}" --spp 4000000 --time-budget 0.3 --checkpoint 0.01 \
    --resume "$disk/saved.ckpt" --out "$WORK/resumed.exr"
done

echo "$((cases - failures)) passed, $failures failed"
[ "$failures" = 0 ]
