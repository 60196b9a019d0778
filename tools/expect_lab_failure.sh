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
lab=$1 binary=$2 spec=$3 mutant=${4:-}
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
# Catch2 prints the failing test's name between two lines of dashes.
failed=$(awk '/^-----------/ { getline; print; exit }' "$log")
echo "lab check: lab $lab's tests '$spec' fail with the $what, as they must (exit $rc): first \"$failed\""
