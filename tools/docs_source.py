"""Finds code in the project's source files for tools/docs_check.py: a marked region or the
definition of a function or struct by name, with the comment lines above it, and the line
where a symbol is defined."""
import os
import re


def read_lines(path):
    with open(path, encoding="utf-8") as f:
        return f.read().split("\n")


def dedent(lines):
    indents = [len(l) - len(l.lstrip(" ")) for l in lines if l.strip()]
    cut = min(indents) if indents else 0
    return [l[cut:].rstrip() for l in lines]


def marked_region(lines, name):
    """(first line index, lines) of the region between [excerpt name] and [/excerpt]."""
    start = None
    for i, line in enumerate(lines):
        if re.search(r"\[excerpt " + re.escape(name) + r"\]", line):
            start = i + 1
        elif start is not None and "[/excerpt]" in line:
            return start, lines[start:i]
    return None


NOT_TYPES = {"return", "else", "case", "new", "delete", "throw", "if", "while", "for", "switch", "co_return"}


def definition_line(lines, name):
    """Index of the definition of function or struct `name`: a line `Type name(` (any
    indentation; at column 0 the type may be absent, as for Class::Class) or `struct name`,
    which is not a statement (does not end with ';')."""
    n = re.escape(name)
    func = re.compile(r"^(\s*)((?:[\w:<>*&,]+\s+)*)(?:[\w<>]+::)*" + n + r"\s*\(")
    struct = re.compile(r"^\s*(struct|class)\s+" + n + r"\b(?!.*;\s*$)")
    for i, line in enumerate(lines):
        stripped = line.strip()
        if not stripped or stripped.startswith(("//", "#", "*", "/*")) or stripped.endswith(";"):
            continue
        if struct.search(line):
            return i
        m = func.match(line)
        if not m:
            continue
        types = m.group(2).split()
        if any(t in NOT_TYPES for t in types):
            continue
        if types or m.group(1) == "":
            return i
    return None


def block_end(lines, i):
    """Index of the line closing the block that starts at line i: the first later line
    that is the definition's indentation followed by '}' (or the same line if it closes)."""
    indent = lines[i][:len(lines[i]) - len(lines[i].lstrip())]
    if lines[i].rstrip().endswith("}"):
        return i
    for j in range(i + 1, len(lines)):
        if lines[j].startswith(indent + "}"):
            return j
    return None


def find_symbol(lines, name):
    """The line index where `name` is defined: a marked excerpt, a function or struct, a #define, a constant, or else the first declaration `Type name =|;|(`."""
    region = marked_region(lines, name)
    if region:
        return region[0]
    i = definition_line(lines, name)
    if i is not None:
        return i
    n = re.escape(name)
    patterns = [r"^\s*#\s*define\s+" + n + r"\b",
                r"^\s*(static\s+)?(inline\s+)?(const|constexpr)\s+[\w:<>]+\s+" + n + r"\b",
                r"^\s*[\w:<>]+\s+" + n + r"\s*(=|;|\(|\{)"]
    for p in patterns:
        rx = re.compile(p)
        for i, line in enumerate(lines):
            if rx.search(line):
                return i
    return None


def excerpt_text(root, path, name):
    """The lines of excerpt `name` of `path`, or an error string."""
    full = os.path.join(root, path)
    if not os.path.isfile(full):
        return None, f"{path} does not exist"
    lines = read_lines(full)
    region = marked_region(lines, name)
    if region:
        return dedent(region[1]), None
    i = definition_line(lines, name)
    if i is None:
        return None, f"{path} has no '[excerpt {name}]' marker and no top-level definition of {name}"
    # Back up over the comment lines just above the definition.
    indent = lines[i][:len(lines[i]) - len(lines[i].lstrip())]
    start = i
    while start > 0 and lines[start - 1].startswith(indent + "//"):
        start -= 1
    end = block_end(lines, i)
    if end is None:
        return None, f"{path}: the definition of {name} at line {i + 1} has no closing '}}'"
    return dedent(lines[start:end + 1]), None
