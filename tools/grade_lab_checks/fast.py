"""The quick part of tools/test_grade_lab.py (--fast, ctest entry grade_lab_fast; tooling for
teachers, not a part of the article): bad usage, no bubblewrap, the source check, the
sandbox's walls, the report, a crash's test, the tests' shards, the lab pages' hint tables,
the CSV's quoting, the rebuilds."""
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile

from grade_lab_checks.fixtures import lab2_fixtures, lab4_fixtures
from grade_lab_checks.fixtures_small import lab1_fixtures, lab3_fixtures, lab5_fixtures, lab6_fixtures
from grade_lab_checks.support import HERE, REPO, TOOL, expect, reference, write


def bad_usage(tmp):
    subs = os.path.join(tmp, "empty")
    os.makedirs(subs)
    for args, what in (([], "no arguments"), (["2"], "no submissions folder"), (["7", subs], "lab 7"),
                       (["2", os.path.join(tmp, "missing")], "a missing folder"), (["2", subs], "an empty folder")):
        r = subprocess.run([sys.executable, TOOL] + args, capture_output=True, text=True)
        expect(r.returncode == 2 and r.stdout == "" and len(r.stderr.strip().splitlines()) == 1
               and r.stderr.startswith("grade_lab: "), f"bad usage ({what}) exits 2 with one line", r.stderr)


def no_sandbox_refused(tmp):
    """With no bwrap on PATH the grader says so in one line, exits 1 and grades nothing."""
    bin_dir, subs = os.path.join(tmp, "bin_without_bwrap"), os.path.join(tmp, "one")
    os.makedirs(bin_dir)
    os.makedirs(subs)
    for tool in ("cmake", "ctest", "prlimit", "setpriv"):
        if shutil.which(tool):
            os.symlink(shutil.which(tool), os.path.join(bin_dir, tool))
    write(subs, {"alice.glsl": reference("common/kernel/uniform_hemisphere.glsl")})
    r = subprocess.run([sys.executable, TOOL, "2", subs, "--work", os.path.join(tmp, "work_unused")],
                       capture_output=True, text=True, env={**os.environ, "PATH": bin_dir})
    expect(r.returncode == 1 and r.stdout == "" and len(r.stderr.strip().splitlines()) == 1
           and "bubblewrap" in r.stderr and "--unsealed" in r.stderr,
           "without bubblewrap: one line that says so and names --unsealed, exit 1, nothing graded", r.stderr)


LAB_FIXTURES = {1: lab1_fixtures, 2: lab2_fixtures, 3: lab3_fixtures, 4: lab4_fixtures, 5: lab5_fixtures, 6: lab6_fixtures}


def source_checks(tmp):
    """The honest fixtures pass the source check; each attack is refused, with its reason."""
    from grading.source_check import check_source
    from make_lab_handout import REFERENCE_FILES
    refs = sorted({r for rels in REFERENCE_FILES.values() for r in rels})
    refused_by_lab = {}
    for lab, fixtures in LAB_FIXTURES.items():
        subs = os.path.join(tmp, f"fixtures_lab{lab}")
        os.makedirs(subs)
        fixtures(subs)
        found = {}
        for entry in sorted(os.listdir(subs)):
            folder = os.path.join(subs, entry)
            path = os.path.join(folder, f"lab{lab}.glsl") if os.path.isdir(folder) else folder
            if os.path.isfile(path):
                found[entry.replace(".glsl", "")] = check_source(open(path, "rb").read(), f"labs/lab{lab}.glsl", refs, REPO)
        refused = {n: why for n, why in found.items() if why}
        expect(sorted(refused) == ["r_includes_reference", "r_prints_1gb", "r_rewrites_report", "r_writes_outside"],
               f"the source check refuses lab {lab}'s four attacks and nothing else", repr(refused))
        refused_by_lab[lab] = refused
    refused = refused_by_lab[2]
    expect(refused["r_includes_reference"] == "labs/lab2.glsl:1: includes the reference solution "
                                              "common/kernel/uniform_hemisphere.glsl", "it names the reference included")
    expect(all("'#ifdef __cplusplus'" in refused[n] for n in ("r_prints_1gb", "r_rewrites_report", "r_writes_outside")),
           "it names the C++ hidden from GLSL", repr(refused))
    for code, what in ((b'#ifndef GL_SPIRV\n#define GL_SPIRV\nint x;\n#endif\n', "a guard on a name GLSL defines"),
                       (b"#define CHECK(x) (void)0\n", "a #define of a test macro"),
                       (b'%:include "common/kernel/box_slab.glsl"\n', "a digraph #include"),
                       (b'#  include </etc/passwd>\n', "an #include <...>"),
                       (b'#include "../../tests/common/kernel/test_light_sampling.cpp"\n', "an #include of a test")):
        expect(check_source(code, "labs/lab2.glsl", refs, REPO) is not None, f"the source check refuses {what}")


def sandbox_checks(tmp):
    """The sandbox's walls, tried with small commands."""
    from grading.sandbox import Limits, MiB, Sandbox, memory_limit, probe
    why = probe()
    if why:
        print(f"SKIPPED: the sandbox cannot run here: {why}")
        return False
    run = os.path.join(tmp, "run")
    os.makedirs(run)
    box = Sandbox(True, REPO, {}, {})
    box.owner_of_writable(run)
    limits = Limits(20, memory_limit(), 64, 4 * MiB, 2 * MiB, 2 * MiB)
    outside = os.path.join(tmp, "outside.txt")
    script = (f"echo in > {run}/inside.txt; echo out > {outside}; echo repo > {REPO}/planted_by_sandbox_test; "
              f"ls {REPO} >/dev/null 2>&1 && echo SEES_REPO; echo tmp > /tmp/t && echo TMP_OK; "
              f"python3 -c \"import socket; socket.create_connection(('1.1.1.1', 80), timeout=3)\" 2>/dev/null "
              f"&& echo NET_OK; echo '<fake/>' > {run}/report.xml; echo real > {{report}}; exit 0")
    r = box.run(["bash", "-c", script], run, [run], [], {}, limits, 60, report=True)
    out = r.stdout.decode()
    expect(os.path.isfile(os.path.join(run, "inside.txt")), "the sandbox writes its own folder")
    expect(not os.path.exists(outside) and not os.path.exists(os.path.join(REPO, "planted_by_sandbox_test")),
           "the sandbox writes nothing outside its folder", out)
    expect("SEES_REPO" not in out and "TMP_OK" in out and "NET_OK" not in out,
           "the sandbox sees no project tree and no network, and has a /tmp of its own", out)
    expect(r.report == b"real\n", "the report comes over the grader's pipe, whatever files the sandbox writes",
           repr(r.report))
    r = box.run(["bash", "-c", "head -c 1073741824 /dev/zero"], run, [run], [], {}, limits, 60)
    expect(r.over_cap == "stdout" and len(r.stdout) == limits.stdout_cap and r.seconds < 30,
           "1 GB on stdout is cut off at the cap and the command killed", f"{r.over_cap} {len(r.stdout)} {r.seconds}")
    r = box.run(["bash", "-c", "head -c 10000000 /dev/zero > big"], run, [run], [], {}, limits, 60)
    expect(r.rc != 0 and os.path.getsize(os.path.join(run, "big")) <= limits.file_size,
           "a file over the size limit is cut off", f"rc {r.rc}")
    r = box.run(["bash", "-c", "while :; do :; done"], run, [run], [], {}, limits, 2, on_timeout=lambda pid: "spin()")
    expect(r.timed_out and r.running_function == "spin()" and r.seconds < 10,
           "an endless loop is killed at the deadline, after on_timeout said where it was")
    return True


def report_checks():
    """A report with text besides Catch2's, or a test the lab does not run, is not taken."""
    from grading.lab_tests import read_report
    doc = ('<?xml version="1.0" encoding="UTF-8"?>\n<Catch name="pt_tests">\n  <Group name="pt_tests">\n'
           '    <TestCase name="a; b, c" tags="[x]">\n      <OverallResult success="true"/>\n    </TestCase>\n'
           '    <TestCase name="d" tags="[x]">\n      <Expression success="false" type="CHECK">\n'
           '        <Original>mean == 2</Original>\n        <Expanded>1.013 == 2</Expanded>\n      </Expression>\n'
           '      <OverallResult success="false"/>\n    </TestCase>\n  </Group>\n</Catch>\n')
    rep = read_report(doc.encode(), ["a; b, c", "d"])
    expect(rep.whole and rep.problem is None and rep.cases[0][:2] == ("a; b, c", True)
           and rep.cases[1][2] == "its check mean == 2 failed with 1.013 == 2", "a whole report is read", repr(rep.cases))
    expect(read_report((doc + doc).encode(), ["a; b, c", "d"]).problem is not None, "two reports are refused")
    expect(read_report(("hello\n" + doc).encode(), ["a; b, c", "d"]).problem is not None, "text before it is refused")
    expect(read_report(doc.encode(), ["a; b, c"]).problem is not None, "a test the lab does not run is refused")
    cut = read_report(doc[:doc.index("<OverallResult success=\"false")].encode(), ["a; b, c", "d"])
    expect(not cut.whole and cut.running == "d" and cut.problem is None, "a report cut short names the running test")
    # Cut at the cap in the middle of a test whose check fails on every pixel: its first failure
    # is kept (the grader's FAIL, not REFUSED, tools/grading/submission.py).
    expect(cut.running_failure == "its check mean == 2 failed with 1.013 == 2",
           "a report cut short keeps the running test's first failure", repr(cut.running_failure))
    # A garbled report: REFUSED from a program that exited, CRASH from one that died of a signal.
    from grading.sandbox import Result
    from grading.submission import Grade, judge
    garbled = read_report((doc[:200] + "<<" + doc[200:]).encode(), ["a; b, c", "d"])
    verdicts = []
    for rc in (1, 255, -11, 139):
        g, r = Grade("x", "x.glsl"), Result()
        r.rc = rc
        judge(g, {"tests": ["a; b, c", "d"], "args": None}, r, garbled, 0)
        verdicts.append(g.verdict)
    expect(garbled.problem is not None and verdicts == ["REFUSED", "REFUSED", "CRASH", "CRASH"],
           "a garbled report is REFUSED, or the CRASH of a program that died of a signal", repr(verdicts))
    fine = read_report(doc[:doc.index("<TestCase name=\"d\"") + 40].encode(), ["a; b, c", "d"])
    expect(fine.running == "d" and fine.running_failure is None, "a running test with no failed check has none",
           repr(fine.running_failure))


def crash_names_its_test(pt_tests, tmp, runs=6):
    """A test program whose two threads die of SIGSEGV at once (pt_tests' hidden crash probe,
    tests/test_main.cpp; Catch2's own handler garbled its report then, or died of SIGABRT) dies
    of SIGSEGV with one line on stderr, and the verdict is CRASH SIGSEGV in that test: by the
    name the program wrote as the test started, and by its report alone."""
    from grading.lab_tests import read_report, running_test
    from grading.sandbox import Result
    from grading.submission import Grade, judge
    probe = "grader: two threads die of SIGSEGV at once"
    details = set()
    for k in range(runs):
        report, running = os.path.join(tmp, f"probe{k}.xml"), os.path.join(tmp, f"probe{k}.txt")
        done = subprocess.run([pt_tests, "[crash_probe]", "-r", "xml", "-o", report], capture_output=True,
                              env={**os.environ, "PT_TEST_RUNNING_FILE": running}, timeout=60)
        g, r = Grade("x", "x.glsl"), Result()
        r.rc, r.running_test = done.returncode, running_test(running, [probe])
        rep = read_report(open(report, "rb").read() if os.path.exists(report) else b"", [probe])
        judge(g, {"tests": [probe], "args": None}, r, rep, 0)
        details.add(f"{g.verdict} {g.detail}")
        g, r.running_test = Grade("x", "x.glsl"), None
        judge(g, {"tests": [probe], "args": None}, r, rep, 0)
        details.add(f"{g.verdict} {g.detail}")
        details.add(f"rc {done.returncode}: " + done.stderr.decode(errors="replace").strip().splitlines()[-1])
    expect(details == {f'CRASH SIGSEGV in "{probe}"', f'rc -11: FATAL SIGSEGV in test "{probe}"'},
           "a crash in two threads at once names its test", repr(details))
    expect(running_test(running, ["another test"]) is None, "a name that is not one of the lab's tests is not taken")


def hint_tables(pt_tests):
    """Every lab page has the table, and each of its rows names a test of the lab's program."""
    from grading.hints import matches, read_hints
    names = []
    if pt_tests:
        listing = subprocess.run([pt_tests, "--list-test-names-only"], capture_output=True, text=True)
        names = [n.strip() for n in listing.stdout.splitlines() if n.strip()]
    for lab in range(1, 7):
        hints = read_hints(REPO, lab)
        expect(len(hints) >= 2, f"docs/labs/lab{lab}.md has the table 'If a test fails'")
        for pattern, suspect in hints:
            expect(not names or any(matches(pattern, n) for n in names),
                   f"lab {lab}: the row '{pattern[:60]}' names a test of pt_tests")


def csv_quoting(tmp):
    from grading.reports import write_csv
    from grading.submission import Grade
    g = Grade("alice", "/x/alice.glsl")
    g.verdict, g.detail, g.failed, g.suspect = "FAIL", '"t; u, v": its check a, b failed', ["t; u, v", "w"], "x, y"
    write_csv(tmp, [g])
    rows = list(csv.reader(open(os.path.join(tmp, "grades.csv"), encoding="utf-8", newline="")))
    expect(len(rows) == 2 and rows[1][:4] == ["alice", "FAIL", g.detail, "x, y"] and rows[1][7] == "t; u, v\nw",
           "grades.csv keeps a field with ',' ';' and quotes whole (Python's csv module)", repr(rows))


def rebuilt_outputs(tmp):
    """A submission rebuilds what #includes the lab file (its depfiles) and what is made from
    that, not the GPU kernels that name every labs/*.glsl in a glob rule; the file gets the
    setup's time stamp, so that make does not remake those either."""
    from grading.depends import dependents, put_lab_file
    build, lab = os.path.join(tmp, "deps", "build"), os.path.join(tmp, "deps", "src", "labs", "lab2.glsl")
    os.makedirs(os.path.join(build, "CMakeFiles", "k.dir"))
    os.makedirs(os.path.dirname(lab))
    with open(os.path.join(build, "CMakeFiles", "k.dir", "build.make"), "w") as fh:
        fh.write(f"k_spirv.h: {lab}\n\nCMakeFiles/k.dir/k.cpp.o: k_spirv.h\n\nlibk.a: CMakeFiles/k.dir/k.cpp.o\n"
                 f"libk.a: CMakeFiles/k.dir/cpu.cpp.o\n\nbin/stage: libk.a\n")
    with open(os.path.join(build, "CMakeFiles", "k.dir", "cpu.cpp.o.d"), "w") as fh:
        fh.write(f"CMakeFiles/k.dir/cpu.cpp.o: /src/cpu.cpp \\\n {lab}\n")
    with open(os.path.join(build, "CMakeFiles", "k.dir", "k.cpp.o.d"), "w") as fh:
        fh.write(f"CMakeFiles/k.dir/k.cpp.o: /src/k.cpp {os.path.join(build, 'k_spirv.h')}\n")
    outputs = put_lab_file(build, lab, b"vec3 f() { return vec3(0.0f); }\n", 1_000_000_000)
    expect(sorted(outputs) == ["CMakeFiles/k.dir/cpu.cpp.o", "bin/stage", "libk.a"] and os.stat(lab).st_mtime_ns == 1_000_000_000,
           "a submission rebuilds the objects that include its file and what they make, not the GPU kernels", repr(outputs))
    expect(dependents(build, lab) == set(outputs), "dependents() is what put_lab_file deletes")


def shard_checks(pt_tests, tmp):
    """The shards a submission's tests run in (grading/shards.py): the spec's terms, a split of
    about equal time, the durations the repository ships under the ones a work folder recorded,
    the reports merged in the one run's order; and, with the real pt_tests, that lab 2's tests
    listed file by file are its tests, each once."""
    from grading.lab_tests import read_report, test_names
    from grading.shards import merge_reports, plan, read_durations, shard_specs, spec_terms, tests_by_file
    from grading.lab_tests import test_files
    spec = '[stage2]~[ggx]~"sampling: a mixed, material*",[sampling]~[ggx]'
    expect(spec_terms(spec) == ['[stage2]~[ggx]~"sampling: a mixed, material*"', "[sampling]~[ggx]"],
           "a spec's terms split at the commas outside quotes")
    expect(shard_specs([spec], ["f", "g"])[0].count("[#") == 4, "a shard's spec is each term with each file's tag")
    by_file = {"a": ["a1", "a2"], "b": ["b1"], "c": ["c1"], "d": ["d1", "d2", "d3"]}
    groups = plan(by_file, {"a1": 7.0, "a2": 4.0, "b1": 6.0, "c1": 1.0, "d1": 1.0, "d2": 1.0}, 2)
    expect(sorted(groups) == [["a", "c"], ["b", "d"]], "the files split by their tests' time, unknown tests at the mean",
           repr(groups))
    expect(plan(by_file, {}, 8) == [["d"], ["a"], ["b"], ["c"]], "no more shards than files; before any time, a test counts 1",
           repr(plan(by_file, {}, 8)))
    recorded = os.path.join(tmp, "test_durations.json")
    shipped = read_durations(recorded, 2)
    name = next(iter(shipped), None)
    expect(len(shipped) > 10 and all(s >= 0 for s in shipped.values()), "the repository ships lab 2's durations",
           repr(len(shipped)))
    with open(recorded, "w", encoding="utf-8") as fh:
        json.dump({name: 1234.5}, fh)
    merged = read_durations(recorded, 2)
    expect(merged[name] == 1234.5 and len(merged) == len(shipped) and read_durations(recorded) == {name: 1234.5},
           "a work folder's recorded durations win over the shipped ones, which fill in the rest", repr(merged.get(name)))
    one = ('<?xml version="1.0" encoding="UTF-8"?>\n<Catch name="t">\n  <Group name="t">\n'
           '    <TestCase name="{}" tags="[x]">\n      <OverallResult success="true" durationInSeconds="1.5"/>\n'
           '    </TestCase>\n  </Group>\n</Catch>\n')
    rep = merge_reports([read_report(one.format("b1").encode(), ["b1"]), read_report(one.format("a1").encode(), ["a1"])],
                        ["a1", "b1"])
    expect([c[0] for c in rep.cases] == ["a1", "b1"] and rep.whole and rep.durations == {"a1": 1.5, "b1": 1.5},
           "the shards' reports merge in the one run's order, with each test's seconds", repr(rep.cases))
    if pt_tests:
        specs = ['[stage2]~[ggx]~[energy]~"sampling: a mixed material*"~[compare]~[mutants],[sampling]~[ggx]']
        build, target = os.path.dirname(os.path.dirname(pt_tests)), os.path.basename(pt_tests)
        listed = sorted(n for names in tests_by_file(pt_tests, specs, test_files(build, specs, target)).values()
                        for n in names)
        names = sorted(test_names(build, specs, target))
        expect(len(names) > 10 and listed == names, "lab 2's tests listed file by file are its tests, each once",
               f"{len(listed)} listed, {len(names)} tests")


def fast(pt_tests):
    sys.path.insert(0, HERE)
    with tempfile.TemporaryDirectory(prefix="grade_lab_fast_") as tmp:
        rebuilt_outputs(tmp)
        bad_usage(tmp)
        no_sandbox_refused(tmp)
        source_checks(tmp)
        report_checks()
        shard_checks(pt_tests, tmp)
        if pt_tests:
            crash_names_its_test(pt_tests, tmp)
        hint_tables(pt_tests)
        csv_quoting(tmp)
        sealed = sandbox_checks(tmp)
    return 0 if sealed else 77
