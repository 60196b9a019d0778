#!/usr/bin/env bash
# The lab check (docs/labs/README.md, cmake/Labs.cmake): runs the tests of lab N in the
# check build with lab N's stubs selected (PT_LAB_STUB=N), or with one of its known-wrong
# answers (PT_LAB_MUTANT=NAME, labs/mutants.h), and passes only if they FAIL, by an
# assertion rather than a crash, after the stub or the mutant said it ran. This is what
# shows that a lab's tests grade the function the student writes (the article's Eq. 2 to 5,
# one lab each, lab 5's slab test of the BVH that follows the article, and lab 6's MIS
# weights of stage5), and that they catch the classic mistakes in it.
# usage: tools/expect_lab_failure.sh N PT_TESTS_BINARY CATCH2_TEST_SPEC [MUTANT]
set -uo pipefail
if [ $# -ne 3 ] && [ $# -ne 4 ]; then
  echo "usage: $0 LAB_NUMBER PT_TESTS_BINARY CATCH2_TEST_SPEC [MUTANT]" >&2
  exit 2
fi
lab=$1 binary=$2 spec=$3 mutant=${4:-} spec_arg=$3
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if [ -n "$mutant" ]; then
  what="mutant $mutant" ran="^lab $lab: mutant $mutant runs in place of the reference"
  export PT_LAB_MUTANT=$mutant
else
  what="stubs" ran="^lab $lab: .* is not written yet"
  export PT_LAB_STUB=$lab
fi
# The tests that start the programs ([cli]) are left out: the program inherits the stub or
# the mutant, but says so on the test's pipe, not in this log, so a failure there could not
# be told from one of another cause.
spec=$(printf '%s' "$spec" | sed 's/,/~[cli],/g; s/$/~[cli]/')
# The test that caught this stub or mutant when the list was last written (first_failures,
# below) runs first, alone and within the same spec: one of the spec's tests failing by an
# assertion after the stub or the mutant ran is the verdict the whole run gives, found in a
# few seconds instead of after every test that comes before it by name (issue #51: under
# AddressSanitizer that was up to 30 s an entry). Where that test does not catch it (renamed,
# or the lab's code changed), the whole spec runs, as below, and says which test to write down.
first_failures=$(dirname "$0")/lab_check_first_failures.txt
key="stubs $lab $spec_arg"
[ -n "$mutant" ] && key="mutant $mutant"
recorded=$(awk -F'\t' -v key="$key" '$1 == key { print $2; exit }' "$first_failures" 2>/dev/null)
first_failing_test() {  # Catch2 prints the failing test's name between two lines of dashes.
  awk '/^-----------/ { getline; print; exit }' "$log"
}
if [ -n "$recorded" ]; then
  # Catch2's spec: the name quoted (its \, " and , escaped), ANDed with each OR'd part of the spec.
  name=$(printf '%s' "$recorded" | sed 's/[\\",]/\\&/g')
  only=$(printf '%s' "$spec" | NAME="\"$name\"" awk 'BEGIN { FS = OFS = ","; name = ENVIRON["NAME"] } { for (i = 1; i <= NF; i++) $i = name $i; print }')
  "$binary" "$only" -# -a >"$log" 2>&1
  rc=$?
  if [ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -q "$ran" "$log" && [ "$(first_failing_test)" = "$recorded" ]; then
    echo "lab check: lab $lab's tests '$spec' fail with the $what, as they must (exit $rc): \"$recorded\" (run first: it caught it before)"
    exit 0
  fi
  echo "lab check: \"$recorded\" alone does not catch the $what (exit $rc): the whole spec runs" >&2
fi
# -#: the [#file] tags that the grader's exclusions use (tools/grading/lab_tests.py). -a: stop at
# the first failing assertion; one failure is all the check needs. --order lex:
# the tests by name, so that each stage's analytic tests ("stage4: ...") run before the
# long ones ("trade: ..."), and a mistake is found in seconds rather than minutes.
"$binary" "$spec" -# -a --order lex >"$log" 2>&1
rc=$?
if [ $rc -eq 0 ]; then
  echo "lab check: lab $lab's tests '$spec' PASS with the $what in place: they do not grade lab $lab" >&2
  exit 1
fi
if [ $rc -ge 128 ]; then
  tail -20 "$log" >&2
  echo "lab check: lab $lab's tests '$spec' crashed (exit $rc) with the $what instead of failing" >&2
  exit 1
fi
if ! grep -q "$ran" "$log"; then
  tail -20 "$log" >&2
  echo "lab check: lab $lab's tests '$spec' failed, but the $what never ran: they fail for another reason" >&2
  exit 1
fi
failed=$(first_failing_test)
echo "lab check: lab $lab's tests '$spec' fail with the $what, as they must (exit $rc): first \"$failed\""
if [ "$failed" != "$recorded" ]; then
  printf 'lab check: write it down in %s, so that it runs first next time:\n%s\t%s\n' "$first_failures" "$key" "$failed"
fi
