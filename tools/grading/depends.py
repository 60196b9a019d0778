"""Which outputs of the lab build depend on the student's file, for tools/grade_lab.py (grading a
class's lab submissions; tooling for teachers, not a part of the article). The graph is the
build's own: CMake's Makefile rules (build.make) and the compilers' depfiles (*.o.d). Only what
really #includes the file is rebuilt: the C++ objects whose depfiles name it, and everything
made from them. The GPU kernels' rules name every labs/*.glsl through a glob, not through their
includes: they stay the setup's (the lab's tests run the CPU backend only; the student's GLSL
is compiled once apart, glsl_check.py), and the file is written with the setup's time stamp so
that make does not remake them either."""
import os
import re


def make_tokens(text):
    """The words of a make rule or depfile: backslash-newlines joined, '\\ ' kept in a name."""
    text = text.replace("\\\n", " ")
    return [t.replace("\\ ", " ") for t in re.findall(r"(?:\\ |[^\s])+", text)]


def build_node(path, cwd, build):
    """A path of a rule or depfile as dependency_graph names it: relative to the build folder
    when inside it, absolute otherwise."""
    p = os.path.normpath(path if os.path.isabs(path) else os.path.join(cwd, path))
    return os.path.relpath(p, build) if p.startswith(build + os.sep) else p


def add_rule_edges(users, path, build):
    """Adds the rules of CMake's Makefile path (a build.make) to users."""
    lines = open(path, encoding="utf-8", errors="replace").read().replace("\\\n", " ").splitlines()
    for line in lines:
        if not line or line[0] in "\t#" or ":" not in line or line.startswith("."):
            continue
        m = re.match(r"^((?:\\ |[^\s:])+)\s*:(?!=)(.*)$", line)
        if not m:
            continue
        target = build_node(make_tokens(m.group(1))[0], build, build)
        for dep in make_tokens(m.group(2)):
            users.setdefault(build_node(dep, build, build), set()).add(target)


def add_depfile_edges(users, path, build):
    """Adds a compiler's depfile path (an *.o.d) to users."""
    tokens = make_tokens(open(path, encoding="utf-8", errors="replace").read())
    if not tokens or not tokens[0].endswith(":"):
        return
    # gcc runs in the target's folder, the part of the path before CMakeFiles/.
    cwd = path.split(os.sep + "CMakeFiles" + os.sep)[0]
    target = os.path.relpath(path[:-2], build)
    for dep in tokens[1:]:
        if dep.endswith(":"):  # -MP phony rules
            continue
        users.setdefault(build_node(dep, cwd, build), set()).add(target)


def dependency_graph(build):
    """(rules, includes): prerequisite -> the outputs made from it, from CMake's Makefile rules
    (build.make) and from the compilers' depfiles (*.o.d). Paths inside the build folder are
    relative to it, others absolute."""
    rules, includes = {}, {}
    for root, _, files in os.walk(build):
        for f in files:
            path = os.path.join(root, f)
            if f == "build.make":
                add_rule_edges(rules, path, build)
            elif f.endswith(".o.d"):
                add_depfile_edges(includes, path, build)
    return rules, includes


def dependents(build, lab_file):
    """The outputs of the build (relative to build) made from a C++ object that #includes
    lab_file: those objects, and what is made from them (libraries, programs), transitively."""
    rules, includes = dependency_graph(build)
    seen = {out for out in includes.get(os.path.normpath(lab_file), ()) if not os.path.isabs(out)}
    todo = list(seen)
    while todo:
        node = todo.pop()
        for out in rules.get(node, set()) | includes.get(node, set()):
            if out not in seen:
                seen.add(out)
                todo.append(out)
    return {out for out in seen if not os.path.isabs(out)}  # only what the build made


def delete_dependents(build, lab_file):
    """Deletes every output of dependents(build, lab_file); returns them all, deleted or not there."""
    outputs = dependents(build, lab_file)
    for out in outputs:
        path = os.path.join(build, out)
        if os.path.isfile(path):
            os.remove(path)
    return outputs


def put_lab_file(build, lab_file, code, stamp_ns):
    """Writes code as the work copy's labs/labLAB.glsl, with the time stamp stamp_ns (the
    setup's: the GPU kernels' glob rules then see nothing new), and deletes every output of the
    build that #includes it (dependents); returns those outputs (relative to build)."""
    with open(lab_file, "wb") as fh:
        fh.write(code)
    os.utime(lab_file, ns=(stamp_ns, stamp_ns))
    return delete_dependents(build, lab_file)
