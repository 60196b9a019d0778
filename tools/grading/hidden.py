"""The files a submission must not see, for tools/grade_lab.py (grading a class's lab
submissions; tooling for teachers, not a part of the article): the lab's reference solutions
(hidden from every build and test run) and the held-back tests (hidden from the test runs),
each shown in the sandbox as a placeholder that is an #error saying why."""
import os


def placeholders(work, src, paths, why):
    """{path in src: a placeholder file in WORK/hidden} for each of paths (repository-relative)
    that exists: a file that says why it is not there, with the original's times, so that make
    sees nothing changed and a submission that includes it does not compile."""
    folder = os.path.join(work, "hidden")
    os.makedirs(folder, exist_ok=True)
    hidden = {}
    for rel in paths:
        original = os.path.join(src, rel)
        if not os.path.isfile(original):
            continue
        placeholder = os.path.join(folder, rel.replace(os.sep, "__"))
        with open(placeholder, "w", encoding="utf-8") as fh:
            fh.write(f"#error \"{rel} is {why}: a submission does not see it (tools/grade_lab.py)\"\n")
        st = os.stat(original)
        os.utime(placeholder, ns=(st.st_atime_ns, st.st_mtime_ns))
        hidden[original] = placeholder
    return hidden


def held_back_tests(src):
    """The test sources (repository-relative) that hold a held-back test ([held_back])."""
    found = []
    for root, _, files in os.walk(os.path.join(src, "tests")):
        for f in files:
            path = os.path.join(root, f)
            if f.endswith((".cpp", ".h")) and "[held_back]" in open(path, encoding="utf-8", errors="replace").read():
                found.append(os.path.relpath(path, src))
    return sorted(found)
