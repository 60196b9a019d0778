# What render_array.sh and render_parallel.sh both do once their options are parsed (sourced
# by them, never run): the paths made absolute, pt_merge found, and the split checked and
# its parts named by render_part.sh --list. Uses the caller's out, parts, bin, here and die.

# out, parts (default: beside out) and bin as absolute paths; pt_merge must be in bin.
resolve_split_paths() {
  out=$(realpath -m -- "$out")
  [ -n "$parts" ] || parts=${out%.exr}.parts
  parts=$(realpath -m -- "$parts")
  bin=$(realpath -m -- "$bin")
  [ -x "$bin/pt_merge" ] || die "no program $bin/pt_merge (build it, or give --bin)"
}

# list_split_parts RENDER_PART_ARGS...: render_part.sh --list checks the split (spp, count,
# stage, stage options) and names the parts into part_files; it has said why when it refuses.
list_split_parts() {
  mapfile -t part_files < <("$here/render_part.sh" --list "$@" || echo FAILED)
  [ "${part_files[-1]:-FAILED}" != FAILED ] || exit 2
  mkdir -p "$parts" "$(dirname "$out")"
}
