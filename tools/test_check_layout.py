#!/usr/bin/env python3
"""Test of tools/check_layout.py (the arrows of the house, docs/README.md): in a small tree
of its own, a file in common/ that includes labs/, a stage, cpu/ or gpu/ fails the check,
as do a lower room including a higher one and a stage including another stage; the
allowed includes pass. The stage folders: a stage whose main.cpp runs other steps than the
others', or a folder with a file besides main.cpp, integrator.glsl, README.md and the files
the stage names (included by its integrator, or in its pt_add_stage line), fails.
A source file of over 300 lines in a room of the rule (tests/ included) fails, one of 300
passes. Also: the project's own tree passes.
usage: tools/test_check_layout.py   (ctest entry layout_check_catches_wrong_arrows)"""
import os
import re
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


# What follows a stage's record in a main.cpp of the test tree (the steps, shortened).
PROGRAM = """                        {pt::make_cpu_backend}};
  return pt::run_guarded(stage.info.name, [&] {
    pt::Scene scene = pt::load_stage_scene(*options, stage);
  });
}
"""


def tree(root, files, program=PROGRAM):
    for rel, includes in files.items():
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as fh:
            fh.write("// a file of the test tree\n" + "".join(f'#include "{i}"\n' for i in includes))
            stage = re.match(r"stage(\d+)_\w+/main\.cpp$", rel)
            if stage:
                fh.write(f"int main() {{\n  const pt::Stage stage{{{{}},\n  stage{stage.group(1)}::kernels(),\n" + program)


def run(root):
    return subprocess.run([sys.executable, TOOL, "--root", root], capture_output=True, text=True)


def verdict(ok, what, r):
    """Prints the line of one case (with the checker's output when it failed); 1 if failed."""
    print(("ok" if ok else "FAILED") + ": " + what + ("" if ok else "\n" + r.stdout))
    return 0 if ok else 1


def main():
    failed = 0
    with tempfile.TemporaryDirectory(prefix="layout_test_") as tmp:
        good = os.path.join(tmp, "good")
        tree(good, ALLOWED)
        r = run(good)
        failed += verdict(r.returncode == 0, "the allowed includes pass", r)
        for n, (rel, target) in enumerate(WRONG):
            root = os.path.join(tmp, f"wrong{n}")
            tree(root, dict(ALLOWED, **{rel: ALLOWED.get(rel, []) + [target]}))
            r = run(root)
            failed += verdict(r.returncode == 1 and f"{rel}:" in r.stdout and target in r.stdout,
                              f"{rel} including {target} is caught", r)
        stages = dict(ALLOWED, **{"stage2_montecarlo/main.cpp": [
            i.replace("stage1_raycast", "stage2_montecarlo") for i in ALLOWED["stage1_raycast/main.cpp"]]})
        two = os.path.join(tmp, "two_stages")
        tree(two, stages)
        r = run(two)
        failed += verdict(r.returncode == 0, "two stages running the same steps pass", r)
        drift = os.path.join(tmp, "drift")
        tree(drift, stages)
        tree(drift, {"stage2_montecarlo/main.cpp": stages["stage2_montecarlo/main.cpp"]},
             PROGRAM.replace("    pt::Scene", "    pt::print_banner();\n    pt::Scene"))
        r = run(drift)
        failed += verdict(r.returncode == 1 and "stage2_montecarlo/main.cpp: its program differs" in r.stdout
                          and "print_banner" in r.stdout, "a stage whose program has drifted is caught", r)
        extra = os.path.join(tmp, "extra")
        tree(extra, dict(stages, **{"stage2_montecarlo/cpu_kernel.cpp": []}))
        r = run(extra)
        failed += verdict(r.returncode == 1 and "stage2_montecarlo/cpu_kernel.cpp: a stage folder holds only" in r.stdout,
                          "a stage folder with a file of the build's is caught", r)
        own = os.path.join(tmp, "own")
        tree(own, dict(stages, **{"stage2_montecarlo/integrator.glsl": ["stage2_montecarlo/bounce.glsl"],
                                  "stage2_montecarlo/bounce.glsl": [], "stage2_montecarlo/pilot.cpp": [],
                                  "stage2_montecarlo/pilot.h": []}))
        with open(os.path.join(own, "CMakeLists.txt"), "w", encoding="utf-8") as fh:
            fh.write("pt_add_stage(stage2_montecarlo CPU_GROUPS 1\n  BEFORE_RENDER stage2::f HEADER pilot.h SOURCES pilot.cpp)\n")
        r = run(own)
        failed += verdict(r.returncode == 0, "a stage's own files, included by its integrator or named by its "
                          "pt_add_stage line, pass", r)
        tree(own, {"stage2_montecarlo/unnamed.glsl": []})
        r = run(own)
        failed += verdict(r.returncode == 1 and "stage2_montecarlo/unnamed.glsl: a stage folder holds only" in r.stdout
                          and "bounce.glsl" not in r.stdout and "pilot.cpp" not in r.stdout,
                          "a stage file that the stage does not name is caught", r)
        step = os.path.join(tmp, "step")
        tree(step, dict(ALLOWED, **{"stage4_direct_indirect/integrator.glsl": [], "stage5_mis/integrator.glsl": [], "common/render/render.cpp": []}))
        r = run(step)
        failed += verdict(r.returncode == 0, "stage5's integrator as stage4's passes", r)
        with open(os.path.join(step, "stage5_mis/integrator.glsl"), "a", encoding="utf-8") as fh:
            fh.write("".join(f"float idea{i}();\n" for i in range(61)))
        with open(os.path.join(step, "common/render/render.cpp"), "a", encoding="utf-8") as fh:
            fh.write("// runs stage5's MIS pilot\n")
        r = run(step)
        failed += verdict(r.returncode == 1 and "stage5_mis/integrator.glsl: 61 lines differ" in r.stdout
                          and "common/render/render.cpp: names the MIS pilot" in r.stdout,
                          "a stage5 far from stage4 plus MIS, and a pilot in common/, are caught", r)
        long = os.path.join(tmp, "long")
        tree(long, ALLOWED)
        for rel, count in (("tools/at_limit.py", 300), ("gpu/at_limit.cpp", 300), ("tests/at_limit_test.cpp", 300),
                           ("stage1_raycast/integrator.glsl", 10)):
            os.makedirs(os.path.dirname(os.path.join(long, rel)), exist_ok=True)
            with open(os.path.join(long, rel), "w", encoding="utf-8") as fh:
                fh.write("// line\n" * count)
        r = run(long)
        failed += verdict(r.returncode == 0, "files of 300 lines pass", r)
        for rel in ("tools/grading/too_long.py", "common/kernel/too_long.glsl", "bench/too_long.sh",
                    "docs/figures/too_long.py", "stage1_raycast/main.cpp", "tests/stages/too_long_test.cpp"):
            root = os.path.join(tmp, "long_" + rel.replace("/", "_"))
            tree(root, ALLOWED)
            os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
            with open(os.path.join(root, rel), "a", encoding="utf-8") as fh:
                fh.write("// line\n" * 301)
            r = run(root)
            failed += verdict(r.returncode == 1 and f"{rel}: " in r.stdout and "lines (at most 300)" in r.stdout,
                              f"{rel} longer than 300 lines is caught", r)
    r = run(os.path.dirname(HERE))
    failed += verdict(r.returncode == 0, "the project's tree follows the arrows", r)
    print(f"check_layout test: {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
