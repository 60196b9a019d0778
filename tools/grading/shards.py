"""A submission's tests as shards run side by side, for tools/grade_lab.py (issue #47: at most
30 s a submission on 2 cores; tooling for teachers, not a part of the article). Catch2 runs its
tests one after another and most of a lab's tests keep about one core busy, so the grader splits
them into --jobs shards of about equal time, each a sealed run with a report pipe of its own,
and merges what they report. A shard is a set of test files: Catch2's [#file] tags need no
escaping, where a test's name may hold the ',' that a spec cannot. The split follows each test's
duration in the last submission that passed (WORK/test_durations.json), over the durations the
repository ships (typical_durations.json, beside this file: seconds per test of each lab's correct
submission on the project's 2-core machine, 2026-12-07; the held-back tests left out, whose names
the students do not see), so that the first submission after a fresh set-up is split as well as
the next (issue #47: lab 4's took 32.4 s without them, 29.4 s with them); a test in neither counts
as the mean of the known."""
import functools
import json
import os
import subprocess

from .lab_tests import Report
from .sandbox import Result


def spec_terms(spec):
    """The comma-separated terms of a Catch2 spec (Catch2 ORs them); commas inside quotes stay."""
    terms, current, quoted = [], "", False
    for c in spec:
        if c == '"':
            quoted = not quoted
        if c == "," and not quoted:
            terms.append(current)
            current = ""
        else:
            current += c
    return terms + [current] if current else terms


def tests_by_file(binary, specs, files):
    """{file tag: the names of the tests that specs select in that file} (files: the [#file]
    tags without '#'), listed by the test program once per file."""
    found = {}
    for f in files:
        listing = subprocess.run([binary, "-#", "--list-test-names-only"] + shard_specs(specs, [f]),
                                 capture_output=True, text=True)
        names = [line.strip() for line in listing.stdout.splitlines() if line.strip()]
        if names:
            found[f] = names
    return found


def shard_specs(specs, files):
    """The lab's specs restricted to the tests of files: each term ANDed with each file's tag."""
    return [",".join(term + f"[#{f}]" for spec in specs for term in spec_terms(spec) for f in files)]


def plan(by_file, durations, shards):
    """The files in at most `shards` groups of about equal time, the longest file first into the
    group with the least so far (durations: seconds per test name; unknown ones count as the
    mean of the known, or 1)."""
    known = [durations[n] for names in by_file.values() for n in names if n in durations]
    typical = sum(known) / len(known) if known else 1.0
    cost = {f: sum(durations.get(n, typical) for n in names) for f, names in by_file.items()}
    groups = [[] for _ in range(max(1, min(shards, len(by_file))))]
    load = [0.0] * len(groups)
    for f in sorted(cost, key=lambda f: (-cost[f], f)):
        k = load.index(min(load))
        groups[k].append(f)
        load[k] += cost[f]
    return [sorted(g) for g in groups if g]


def read_durations(path, lab=None):
    """{test name: seconds} of WORK/test_durations.json (path), over the shipped ones of lab (if
    given) that it does not hold."""
    shipped = shipped_durations(lab) if lab is not None else {}
    data = read_json(path)
    recorded = data if isinstance(data, dict) else {}
    try:
        return {str(k): float(v) for k, v in {**shipped, **recorded}.items()}
    except (TypeError, ValueError):
        return {}


@functools.lru_cache(maxsize=None)
def shipped_durations(lab):
    """typical_durations.json's seconds for lab, read once per grading run."""
    table = read_json(os.path.join(os.path.dirname(os.path.abspath(__file__)), "typical_durations.json"))
    shipped = table.get(str(lab), {}) if isinstance(table, dict) else {}
    return shipped if isinstance(shipped, dict) else {}


def read_json(path):
    try:
        with open(path, encoding="utf-8") as fh:
            return json.load(fh)
    except (OSError, ValueError):
        return None


def record_durations(path, durations):
    """Adds the seconds of each test of a passing submission to WORK/test_durations.json."""
    if durations:
        merged = {**read_durations(path), **durations}
        with open(path + ".tmp", "w", encoding="utf-8") as fh:
            json.dump(merged, fh, indent=1, sort_keys=True)
        os.replace(path + ".tmp", path)


def merge_reports(reports, order):
    """One Report of the shards' (order: the lab's test names, in the order one run would give
    them): the cases of all, whole when each is, the unfinished test (and why it had failed) and the
    first problem."""
    rep = Report()
    rank = {name: k for k, name in enumerate(order)}
    rep.cases = sorted((c for r in reports for c in r.cases), key=lambda c: rank.get(c[0], len(rank)))
    rep.whole = all(r.whole for r in reports)
    # The unfinished test: one that had failed when its report was cut short, if a shard has it.
    cut = next((r for r in reports if r.running_failure), None) or next((r for r in reports if r.running), None)
    rep.running, rep.running_failure = (cut.running, cut.running_failure) if cut else (None, None)
    rep.problem = next((r.problem for r in reports if r.problem), None)
    rep.durations = {n: s for r in reports for n, s in r.durations.items()}
    return rep


def merge_results(results):
    """One sandbox Result of the shards' runs, as judge() reads it: the worst ending (a signal or
    an exit code), timed out or over a cap when one was, their output one after another, the wall
    time of the longest and the CPU time of all."""
    merged = Result()
    worst = max(results, key=lambda r: (r.timed_out, r.over_cap is not None, r.rc < 0 or r.rc > 128, r.rc != 0))
    merged.rc, merged.timed_out, merged.over_cap = worst.rc, worst.timed_out, worst.over_cap
    merged.running_function = next((r.running_function for r in results if r.running_function), None)
    merged.running_test = worst.running_test
    merged.stdout = b"".join(r.stdout for r in results)
    merged.stderr = b"".join(r.stderr for r in results)
    merged.report = b""  # the shards' reports are read one by one (merge_reports)
    merged.seconds = max(r.seconds for r in results)
    merged.cpu_seconds = sum(r.cpu_seconds for r in results)
    return merged
