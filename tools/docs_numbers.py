"""Numbers that cannot go stale: docs_check's fourth check (not part of the article: machinery
that keeps the book's quoted measurements equal to the files they describe).

A number the docs quote about a picture or a run carries a marker right after it:

    | 576 spp, 8.136 s <!-- numbers: images/stage1_cornell_equal_time.png spp seconds --> |
    an error of 0.0103 <!-- numbers: results/convergence.csv scene=cornell stage=stage5_mis backend=cpu spp=2048 rel_rmse -->
    0.59 of stage4 <!-- numbers: results/convergence.csv scene=cornell backend=cpu spp=16 efficiency[stage=stage5_mis]/efficiency[stage=stage4_direct_indirect] -->

    <!-- numbers: PATH [COLUMN=VALUE ...] KEY ... -->

PATH is relative to the Markdown file (as links are). The last len(KEY) numbers before the
marker on its line (after any earlier marker) are compared, in order, with the KEYs' values
in PATH, each rounded to as many decimals as the docs print:
  - a .png or .exr picture: KEY is a text attribute the programs write (`spp` is `pt:spp`,
    `seconds` is `pt:seconds`, ...; common/app/image_output.cpp), or for a .png
    `mean.R`, `mean.G`, `mean.B`: the mean of that 8-bit channel over the pixels (0 to 255);
  - a .csv table: KEY is a column, of the one row whose COLUMN=VALUE filters all match;
    NAME[COLUMN=VALUE,...] adds or replaces filters for one value, A/B is a ratio, and
    COLUMN=max picks the row with the largest COLUMN (a run's last checkpoint: spp=max);
  - any other file (bench_seconds.txt): KEY `value` is the number the file holds.
--update writes the files' values into the docs at the docs' precision.
"""
import csv
import os
import re
import struct
import zlib

MARKER = re.compile(r"<!--\s*numbers:\s*(.*?)\s*-->")
NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[-+]?\d+)?(?![\w])")
FILTER = re.compile(r"^\w+=[^\[\]/]*$")
TERM = re.compile(r"^([\w:.]+)(?:\[([^\]]*)\])?$")


class Source:
    """The values one file carries, read once per run (cached by path)."""

    def __init__(self, path):
        self.path = path
        self.attrs = None
        self.pixels = None
        self.rows = None


def png_chunks(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("is not a PNG file")
    i = 8
    while i + 8 <= len(data):
        n, kind = struct.unpack(">I4s", data[i:i + 8])
        yield kind, data[i + 8:i + 8 + n]
        i += 12 + n


def png_text(path):
    """The tEXt, zTXt and iTXt attributes of a PNG: {key: value}."""
    attrs = {}
    for kind, body in png_chunks(path):
        if kind == b"tEXt":
            k, v = body.split(b"\0", 1)
            attrs[k.decode("latin-1")] = v.decode("latin-1")
        elif kind == b"zTXt":
            k, rest = body.split(b"\0", 1)
            attrs[k.decode("latin-1")] = zlib.decompress(rest[1:]).decode("latin-1")
        elif kind == b"iTXt":
            k, rest = body.split(b"\0", 1)
            compressed, rest = rest[0], rest[2:]
            _lang, _key, text = rest.split(b"\0", 2)
            attrs[k.decode("latin-1")] = (zlib.decompress(text) if compressed else text).decode("utf-8")
    return attrs


def png_channel_means(path):
    """Mean of each channel of an 8-bit, non-interlaced RGB or RGBA PNG: [R, G, B(, A)]."""
    header, idat = None, b""
    for kind, body in png_chunks(path):
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
    width, height, depth, colour, _c, _f, interlace = header
    channels = {2: 3, 6: 4, 0: 1, 4: 2}.get(colour)
    if depth != 8 or channels is None or interlace:
        raise ValueError("mean.* needs an 8-bit non-interlaced PNG without a palette")
    raw, stride, bpp = zlib.decompress(idat), width * channels, channels
    prev, sums = bytearray(stride), [0] * channels
    for y in range(height):
        kind, row = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if kind == 1:
            for i in range(bpp, stride):
                row[i] = (row[i] + row[i - bpp]) & 255
        elif kind == 2:
            row = bytearray((a + b) & 255 for a, b in zip(row, prev))
        elif kind == 3:
            for i in range(stride):
                row[i] = (row[i] + ((row[i - bpp] if i >= bpp else 0) + prev[i]) // 2) & 255
        elif kind == 4:
            for i in range(stride):
                a, b, c = (row[i - bpp] if i >= bpp else 0), prev[i], (prev[i - bpp] if i >= bpp else 0)
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        for c in range(channels):
            sums[c] += sum(row[c::channels])
        prev = row
    return [s / (width * height) for s in sums]


def exr_text(path):
    """The string, int, float and double attributes of an OpenEXR header: {name: value}."""
    with open(path, "rb") as f:
        data = f.read(1 << 20)
    if data[:4] != b"\x76\x2f\x31\x01":
        raise ValueError("is not an OpenEXR file")
    attrs, i = {}, 8
    while data[i] != 0:
        name_end = data.index(b"\0", i)
        type_end = data.index(b"\0", name_end + 1)
        size, = struct.unpack("<i", data[type_end + 1:type_end + 5])
        name, kind = data[i:name_end].decode(), data[name_end + 1:type_end].decode()
        body = data[type_end + 5:type_end + 5 + size]
        if kind == "string":
            attrs[name] = body.decode("utf-8", "replace")
        elif kind in ("int", "float", "double"):
            attrs[name] = str(struct.unpack({"int": "<i", "float": "<f", "double": "<d"}[kind], body)[0])
        i = type_end + 5 + size
    return attrs


def value_of(source, filters, key):
    """The value of KEY in the file (as a float); raises ValueError naming what is wrong."""
    path = source.path
    ext = os.path.splitext(path)[1].lower()
    if ext in (".png", ".exr"):
        if filters:
            raise ValueError("a picture takes no COLUMN=VALUE filters")
        if key.startswith("mean."):
            if ext != ".png":
                raise ValueError("mean.* is read from .png pictures only")
            if source.pixels is None:
                source.pixels = png_channel_means(path)
            index = "RGBA".find(key[5:])
            if len(key) != 6 or index < 0 or index >= len(source.pixels):
                raise ValueError(f"{key}: no such channel (mean.R, mean.G, mean.B)")
            return source.pixels[index]
        if source.attrs is None:
            source.attrs = png_text(path) if ext == ".png" else exr_text(path)
        for name in (key, "pt:" + key):
            if name in source.attrs:
                return float(source.attrs[name].split()[0])
        raise ValueError(f"has no attribute {key} (it has {', '.join(sorted(source.attrs))})")
    if ext == ".csv":
        if source.rows is None:
            with open(path, newline="", encoding="utf-8") as f:
                source.rows = list(csv.DictReader(f))
        rows = [r for r in source.rows if all(r.get(c) == v for c, v in filters if v != "max")]
        for c in [c for c, v in filters if v == "max"]:  # COLUMN=max: the row with its largest value
            top = max((float(r[c]) for r in rows), default=None)
            rows = [r for r in rows if float(r[c]) == top]
        if len(rows) != 1:
            which = " ".join(f"{c}={v}" for c, v in filters) or "(no filter)"
            raise ValueError(f"{len(rows)} rows match {which}; the filters must pick exactly one")
        if key not in rows[0]:
            raise ValueError(f"has no column {key}")
        return float(rows[0][key])
    if key != "value":
        raise ValueError(f"{key}: a text file's only key is `value`")
    with open(path, encoding="utf-8") as f:
        return float(f.read().split()[0])


def shown(value, quoted):
    """VALUE printed as the docs' QUOTED number is: as many decimals, e-notation if it has one."""
    mantissa = quoted.split("e")[0]
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    if "e" not in quoted:
        return f"{value:.{decimals}f}"
    digits, exponent = f"{value:.{decimals}e}".split("e")
    return f"{digits}e{int(exponent)}"


def evaluate(source, filters, key):
    """KEY is a TERM or TERM/TERM (a ratio); a TERM is a column or attribute, optionally with
    filters of its own: efficiency[stage=stage5_mis]/efficiency[stage=stage4_direct_indirect]."""
    values = []
    for term in key.split("/"):
        m = TERM.match(term)
        if not m:
            raise ValueError(f"{term}: not NAME or NAME[COLUMN=VALUE,...]")
        extra = [tuple(f.split("=", 1)) for f in (m.group(2) or "").split(",") if "=" in f]
        values.append(value_of(source, [f for f in filters if f[0] not in dict(extra)] + extra, m.group(1)))
    if len(values) > 2:
        raise ValueError(f"{key}: at most one / (a ratio of two values)")
    if len(values) == 2 and values[1] == 0:
        raise ValueError(f"{key}: the divisor is 0")
    return values[0] / values[1] if len(values) == 2 else values[0]


def check_numbers(root, md, lines, update, problems, cache=None):
    """Compares each marked number with its file; returns LINES (numbers rewritten under --update)."""
    rel, base = os.path.relpath(md, root), os.path.dirname(md)
    cache = {} if cache is None else cache
    out = []
    for n, line in enumerate(lines, 1):
        pieces, start = [], 0
        for m in MARKER.finditer(line):
            before = line[start:m.start()]
            words = m.group(1).split()
            if not words:
                problems.errors.append(f"{rel}:{n}: a numbers marker names no file")
                pieces.append(line[start:m.end()])
                start = m.end()
                continue
            target, filters, keys = words[0], [], []
            for w in words[1:]:
                (filters.append(tuple(w.split("=", 1))) if FILTER.match(w) else keys.append(w))
            path = os.path.normpath(os.path.join(base, target))
            where = os.path.relpath(path, root)
            numbers = list(NUMBER.finditer(before))
            if not keys or len(numbers) < len(keys):
                problems.errors.append(f"{rel}:{n}: the marker for {where} names {len(keys)} value(s) "
                                       f"but {len(numbers)} number(s) stand before it")
            elif not os.path.isfile(path):
                problems.errors.append(f"{rel}:{n}: {where} (the file of a quoted number) does not exist")
            else:
                source = cache.setdefault(path, Source(path))
                fixed, last = [], 0
                for key, num in zip(keys, numbers[len(numbers) - len(keys):]):
                    quoted = num.group(0)
                    try:
                        actual = shown(evaluate(source, filters, key), quoted)
                    except (ValueError, KeyError, IndexError, OSError, struct.error, zlib.error) as e:
                        problems.errors.append(f"{rel}:{n}: {where} {key}: {e}")
                        actual = quoted
                    if actual != quoted:
                        if update:
                            problems.warnings.append(f"{rel}:{n}: {key} of {where}: {quoted} -> {actual}")
                        else:
                            problems.errors.append(f"{rel}:{n}: the docs say {key} {quoted}, {where} says {actual} "
                                                   f"(run tools/docs_check.py --update)")
                    fixed.append(before[last:num.start()] + (actual if update else quoted))
                    last = num.end()
                before = "".join(fixed) + before[last:]
            pieces.append(before + m.group(0))
            start = m.end()
        out.append("".join(pieces) + line[start:])
    return out


def count_markers(lines):
    return sum(len(MARKER.findall(line)) for line in lines)
