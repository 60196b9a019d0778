#!/usr/bin/env bash
# The lab check (docs/labs/README.md, cmake/Labs.cmake): runs the tests of lab N in the
# check build with lab N's stubs selected (PT_LAB_STUB=N) and passes only if they FAIL, by
# an assertion rather than a crash, after the stub said it ran. This is what shows that a
# lab's tests grade the function the student writes (the article's Eq. 2 to 5, one lab each,
# lab 5's slab test of the BVH that follows the article, and lab 6's MIS weights of stage5).
# usage: tools/expect_lab_failure.sh N PT_TESTS_BINARY CATCH2_TEST_SPEC
set -uo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 LAB_NUMBER PT_TESTS_BINARY CATCH2_TEST_SPEC" >&2
  exit 2
fi
lab=$1 binary=$2 spec=$3
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# -a: stop at the first failing assertion; one failure is all the check needs.
PT_LAB_STUB=$lab "$binary" "$spec" -a >"$log" 2>&1
rc=$?
if [ $rc -eq 0 ]; then
  echo "lab check: lab $lab's tests '$spec' PASS with the stubs in place: they do not grade lab $lab" >&2
  exit 1
fi
if [ $rc -ge 128 ]; then
  tail -20 "$log" >&2
  echo "lab check: lab $lab's tests '$spec' crashed (exit $rc) instead of failing" >&2
  exit 1
fi
if ! grep -q "^lab $lab: .* is not written yet" "$log"; then
  tail -20 "$log" >&2
  echo "lab check: lab $lab's tests '$spec' failed, but no stub of lab $lab ran: they fail for another reason" >&2
  exit 1
fi
echo "lab check: lab $lab's tests '$spec' fail with the stubs, as they must (exit $rc)"
