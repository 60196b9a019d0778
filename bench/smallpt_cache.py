"""The binaries and references of bench/smallpt_compare.py (issue #18, the stages against
smallpt's algorithm): each program copied into --cache-dir/bin/<hash>/ under the build lock,
so that a rebuild during the run cannot mix two versions, and each renderer's reference
rendered once and cached under the binary's hash, size, spp and seed."""
import fcntl
import hashlib
import os
import shutil
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def repo_path(path):
    return path if os.path.isabs(path) else os.path.join(REPO, path)


def log(message):
    print(f"smallpt_compare.py: {message}", file=sys.stderr, flush=True)


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def snapshot(names, bin_dir, cache, lock):
    """Copies each program into cache/bin/<hash12>/; returns {name: (path, hash12)}."""
    fd = None
    if lock and os.path.exists(lock):
        fd = os.open(lock, os.O_RDONLY)
        log(f"locking {lock} to copy the binaries (waits for a build in progress) ...")
        fcntl.flock(fd, fcntl.LOCK_EX)
    try:
        out = {}
        for name in names:
            src = os.path.join(bin_dir, name)
            for _ in range(60):  # a binary being relinked may be missing for a moment
                if os.path.exists(src):
                    break
                time.sleep(10)
            h = sha256(src)[:12]
            dst_dir = os.path.join(cache, "bin", h)
            dst = os.path.join(dst_dir, name)
            if not os.path.exists(dst):
                os.makedirs(dst_dir, exist_ok=True)
                shutil.copy2(src, dst + ".tmp")
                os.replace(dst + ".tmp", dst)
            out[name] = (dst, h)
        return out
    finally:
        if fd is not None:
            fcntl.flock(fd, fcntl.LOCK_UN)
            os.close(fd)


def reference(r, a, cache):
    name = f"{r.key}_{r.digest}_{a.width}x{a.height}_{a.ref_spp}spp_seed{a.ref_seed}.exr"
    path = os.path.join(cache, "refs", name)
    meta = path[:-4] + ".txt"
    if a.fresh_refs or not (os.path.exists(path) and os.path.exists(meta)):
        os.makedirs(os.path.dirname(path), exist_ok=True)
        log(f"reference {r.label}, {a.ref_spp} spp ...")
        t = r.render(a.width, a.height, a.ref_spp, a.ref_seed, a.threads, path)
        with open(meta, "w") as f:
            f.write(f"{t['cpu_s']:.3f} {t['wall_s']:.3f}\n{t['summary']}\n")
        log(f"  {t['cpu_s']:.1f} CPU s, {t['wall_s']:.1f} s wall")
    else:
        log(f"reference {r.label}: cached {os.path.relpath(path, REPO)}")
    with open(meta) as f:
        cpu_s = float(f.readline().split()[0])
        summary = f.readline().strip()
    return path, cpu_s, summary
