"""The renderers of bench/cycles/compare.py (issue 23, the Cycles comparison): a command run
and timed (user + sys CPU s from os.wait4; bench/smallpt_compare.py and bench/sampler_study.py
use it too, through compare.py), Blender's Cycles through render_cycles.py, a stage program,
and each renderer's reference, cached by renderer key, size and spp."""
import datetime
import json
import os
import re
import shlex
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RENDER_CYCLES = os.path.join(REPO, "bench", "cycles", "render_cycles.py")


def slug(text):
    s = re.sub(r"[^A-Za-z0-9]+", "_", text).strip("_")
    return s or "default"


def log(message):
    print(f"compare.py: {message}", file=sys.stderr, flush=True)


def run_timed(cmd):
    """Runs cmd; returns (output, user + sys CPU s of the process and its children, wall s)."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    output = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        raise RuntimeError(f"{shlex.join(cmd)} failed ({proc.returncode}):\n{output[-3000:]}")
    return output, usage.ru_utime + usage.ru_stime, wall


class Cycles:
    name = "cycles"

    def __init__(self, blender, scene, threads):
        self.blender, self.scene, self.threads = blender, scene, threads
        self.label = "Cycles"
        self.key = "cycles"

    def render(self, w, h, spp, seed, out, reference=False):
        cmd = [self.blender, "--factory-startup", "-b", "--python", RENDER_CYCLES, "--",
               "--scene", self.scene, "--width", str(w), "--height", str(h), "--spp", str(spp),
               "--seed", str(seed), "--threads", str(self.threads), "--out", out]
        output, process_cpu, wall = run_timed(cmd)
        m = re.search(r"CYCLES_RENDER cpu_s=(\S+) wall_s=(\S+)", output)
        if not m:
            raise RuntimeError(f"no CYCLES_RENDER line from blender:\n{output[-3000:]}")
        return {"cpu_s": float(m.group(1)), "wall_s": float(m.group(2)),
                "process_cpu_s": process_cpu, "process_wall_s": wall}


class Stage:
    def __init__(self, binary, scene, threads, args, ref_args):
        self.binary, self.scene, self.threads = binary, scene, threads
        self.args, self.ref_args = args, ref_args
        self.name = os.path.basename(binary)
        self.label = self.name + (" " + shlex.join(args) if args else "")
        self.key = self.name + ("_" + slug(" ".join(ref_args)) if ref_args else "")

    def render(self, w, h, spp, seed, out, reference=False):
        cmd = [self.binary, "--scene", self.scene, "--width", str(w), "--height", str(h),
               "--spp", str(spp), "--seed", str(seed), "--backend", "cpu", "--threads", str(self.threads),
               "--out", out] + (self.ref_args if reference else self.args)
        output, cpu, wall = run_timed(cmd)
        return {"cpu_s": cpu, "wall_s": wall, "process_cpu_s": cpu, "process_wall_s": wall,
                "summary": output.strip().splitlines()[-1] if output.strip() else ""}


def reference(renderer, w, h, spp, seed, ref_dir, fresh):
    path = os.path.join(ref_dir, f"{renderer.key}_{w}x{h}_{spp}spp.exr")
    meta = path[:-4] + ".json"
    if fresh or not (os.path.exists(path) and os.path.exists(meta)):
        os.makedirs(os.path.dirname(path), exist_ok=True)
        log(f"reference {renderer.label} {w}x{h} {spp} spp ...")
        t = renderer.render(w, h, spp, seed, path, reference=True)
        with open(meta, "w") as f:
            json.dump(dict(t, spp=spp, seed=seed, width=w, height=h, label=renderer.label,
                           date=datetime.datetime.now(datetime.timezone.utc).isoformat()), f, indent=1)
        log(f"  {t['cpu_s']:.1f} CPU s, {t['process_wall_s']:.1f} s wall")
    else:
        log(f"reference {renderer.label} {w}x{h} {spp} spp: cached {os.path.relpath(path, REPO)}")
    return path
