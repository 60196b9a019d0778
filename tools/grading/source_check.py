"""What tools/grade_lab.py accepts in a student's labs/labN.glsl before it compiles it (grading a
class's lab submissions; tooling for teachers, not a part of the article). The file is compiled
as GLSL and as C++ into the very test program that grades it, so a preprocessor branch on
__cplusplus (or any other) could hide C++ that GLSL never sees: code that reads files, prints,
or rewrites the report in the tests' own process. A lab file may therefore hold GLSL only:
besides its code, #include lines of the kernel's shared files (never a lab's reference
solution), include guards, and nothing else of the preprocessor."""
import os
import re

MAX_BYTES = 256 * 1024  # a lab file is a few kilobytes
INCLUDE_OK = re.compile(r'^(labs/lab_support\.glsl|common/kernel/[A-Za-z0-9_]+\.glsl)$')
DIRECTIVE = re.compile(r"^\s*#\s*([A-Za-z_]\w*)?(.*)$")


def strip_comments(text):
    """text with each comment replaced by a space (newlines kept, so lines keep their numbers)
    and backslash-newlines joined as the preprocessor joins them (then padded back)."""
    out, i, n = [], 0, len(text)
    while i < n:
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" ")
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(" " + "\n" * text.count("\n", i, j))
            i = j
        elif text[i] == '"':
            j = i + 1
            while j < n and text[j] not in '"\n':
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def logical_lines(text):
    """(line number, logical line) with backslash-newline continuations joined."""
    lines, number, pending, start = [], 0, "", 1
    for number, line in enumerate(text.split("\n"), 1):
        if not pending:
            start = number
        if line.endswith("\\"):
            pending += line[:-1]
            continue
        lines.append((start, pending + line))
        pending = ""
    if pending:
        lines.append((start, pending))
    return lines


def check_source(code, lab_file_name, references, tree):
    """None when the submission's bytes may be compiled, else why not (a sentence for REFUSED).
    references: the reference solutions' paths (repository-relative) of every lab; tree: the
    work copy, in which an included file must exist."""
    if len(code) > MAX_BYTES:
        return f"{lab_file_name} is {len(code) // 1024} KiB: a lab file is a few kilobytes"
    if b"\0" in code:
        return f"{lab_file_name} is not a text file (it holds NUL bytes)"
    text = code.decode("utf-8", errors="replace")
    clean = strip_comments(text)
    for token, what in (("??=", "a trigraph"), ("%:", "a digraph of #"), ("_Pragma", "_Pragma")):
        if token in clean:
            line = clean[:clean.index(token)].count("\n") + 1
            return f"{lab_file_name}:{line}: {what} ('{token}'): a lab file is GLSL, with no preprocessor tricks"
    guard = None
    lines = logical_lines(clean)
    for k, (number, line) in enumerate(lines):
        m = DIRECTIVE.match(line)
        if not m:
            continue
        name, rest = m.group(1) or "", m.group(2).strip()
        if name == "include":
            why = check_include(rest, references, tree)
            if why:
                return f"{lab_file_name}:{number}: {why}"
        elif name == "ifndef" and next_directive(lines, k) == ("define", rest) and guard_name_ok(rest, tree, references):
            guard = rest
        elif name == "define" and rest == guard:
            guard = None
        elif name == "endif":
            continue
        else:
            shown = f"#{name} {rest}".strip()[:60]
            return (f"{lab_file_name}:{number}: the preprocessor line '{shown}': a lab file is GLSL that both backends "
                    f"compile alike, so the grader takes no #if/#ifdef/#define/#undef/#pragma (only #include of the "
                    f"kernel's files and include guards)")
    return None


def guard_name_ok(name, tree, references):
    """True when name may guard the file: a name in capitals that neither backend defines by
    itself (GL_*, VULKAN, __*) and no kernel file defines, so that '#ifndef name' is true for
    GLSL and for C++ alike."""
    if not re.fullmatch(r"[A-Z][A-Z0-9_]*", name) or name.startswith("GL_") or name == "VULKAN":
        return False
    return name not in kernel_macros(tree, references)


_macros = {}


def kernel_macros(tree, references):
    """The macros #defined by the files a lab file may include (the kernel's, less the references)."""
    if tree not in _macros:
        found = set()
        paths = [os.path.join(tree, "labs", "lab_support.glsl")]
        for root, _, files in os.walk(os.path.join(tree, "common")):
            paths += [os.path.join(root, f) for f in files]
        for path in paths:
            if os.path.relpath(path, tree) not in references and os.path.isfile(path):
                text = open(path, encoding="utf-8", errors="replace").read()
                found.update(re.findall(r"^\s*#\s*define\s+(\w+)", text, re.M))
        _macros[tree] = found
    return _macros[tree]


def next_directive(lines, k):
    """(name, argument) of the first preprocessor line after lines[k], or None."""
    for _, line in lines[k + 1:]:
        m = DIRECTIVE.match(line)
        if m:
            return (m.group(1) or "", m.group(2).strip())
        if line.strip():
            return None
    return None


def check_include(rest, references, tree):
    """None when '#include rest' names a shared kernel file, else why not."""
    m = re.fullmatch(r'"([^"]*)"', rest)
    if not m:
        return f"'#include {rest[:60]}': only \"labs/lab_support.glsl\" and \"common/kernel/NAME.glsl\" may be included"
    path = m.group(1)
    if os.path.normpath(path) in references:
        return f"includes the reference solution {path}"
    if not INCLUDE_OK.match(path):
        return f"includes \"{path[:80]}\": only \"labs/lab_support.glsl\" and \"common/kernel/NAME.glsl\" may be included"
    if not os.path.isfile(os.path.join(tree, path)):
        return f"includes \"{path}\", which the project does not have"
    return None
