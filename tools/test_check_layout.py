#!/usr/bin/env python3
"""Test of tools/check_layout.py (the arrows of the house, docs/README.md): in a small tree
of its own, a file in common/ that includes labs/, a stage, cpu/ or gpu/ fails the check,
as do a lower room including a higher one and a stage including another stage; the
allowed includes pass. Also: the project's own tree passes.
usage: tools/test_check_layout.py   (ctest entry layout_check_catches_wrong_arrows)"""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "check_layout.py")

ALLOWED = {
    "common/scene/scene.h": ["common/kernel/scene_types.h", "common/base/error.h"],
    "common/app/app.h": ["common/render/render.h", "common/scene/scene.h"],
    "cpu/cpu_backend.cpp": ["common/render/backend.h", "kernel_definitions.glsl"],
    "gpu/gpu_backend.cpp": ["common/render/render.h"],
    "stage1_raycast/main.cpp": ["common/app/app.h", "cpu/cpu_backend.h", "gpu/gpu_backend.h",
                                "stage1_raycast/kernels.h"],
}
WRONG = [
    ("common/kernel/sampling.glsl", "labs/lab2.glsl"),
    ("common/render/render.cpp", "cpu/cpu_backend.h"),
    ("common/app/app.cpp", "gpu/gpu_backend.h"),
    ("common/scene/scene.cpp", "stage1_raycast/kernels.h"),
    ("common/scene/gltf_loader.cpp", "common/render/film.h"),
    ("common/kernel/lights.glsl", "kernel_definitions.glsl"),
    ("cpu/triangle_soa.cpp", "gpu/buffer.h"),
    ("gpu/buffer.cpp", "common/app/options.h"),
    ("stage2_montecarlo/main.cpp", "stage1_raycast/kernels.h"),
]


def tree(root, files):
    for rel, includes in files.items():
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as fh:
            fh.write("// a file of the test tree\n" + "".join(f'#include "{i}"\n' for i in includes))


def run(root):
    return subprocess.run([sys.executable, TOOL, "--root", root], capture_output=True, text=True)


def main():
    failed = 0
    with tempfile.TemporaryDirectory(prefix="layout_test_") as tmp:
        good = os.path.join(tmp, "good")
        tree(good, ALLOWED)
        r = run(good)
        ok = r.returncode == 0
        failed += not ok
        print(("ok" if ok else "FAILED") + ": the allowed includes pass" + ("" if ok else "\n" + r.stdout))
        for n, (rel, target) in enumerate(WRONG):
            root = os.path.join(tmp, f"wrong{n}")
            tree(root, dict(ALLOWED, **{rel: ALLOWED.get(rel, []) + [target]}))
            r = run(root)
            ok = r.returncode == 1 and f"{rel}:" in r.stdout and target in r.stdout
            failed += not ok
            print(("ok" if ok else "FAILED") + f": {rel} including {target} is caught" + ("" if ok else "\n" + r.stdout))
    r = run(os.path.dirname(HERE))
    ok = r.returncode == 0
    failed += not ok
    print(("ok" if ok else "FAILED") + ": the project's tree follows the arrows" + ("" if ok else "\n" + r.stdout))
    print(f"check_layout test: {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
