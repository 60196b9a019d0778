"""The student's file compiled once as GLSL, for tools/grade_lab.py (grading a class's lab
submissions; tooling for teachers, not a part of the article). The lab's tests run the CPU
backend only, so the grader's build keeps the GPU kernels of its setup (depends.py) instead of
compiling the student's file into all five; glslangValidator compiles it here once, in the
GPU kernel of the lab's stage, sealed, so that a file that is C++ but not GLSL is still a
COMPILE ERROR, with glslang's message and warnings."""
import os
import re

from .sandbox import BUILD_LIMITS

# The stage whose GPU kernel (WORK/src/build/STAGE/kernel.comp) holds lab N's functions.
LAB_STAGE = {1: "stage1_raycast", 2: "stage2_montecarlo", 3: "stage3_importance", 4: "stage4_direct_indirect",
             5: "stage4_direct_indirect", 6: "stage5_mis"}
GLSL_TIMEOUT = 300  # seconds


def glslang(build):
    """glslangValidator as the lab build found it (CMakeCache.txt), or None."""
    cache = open(os.path.join(build, "CMakeCache.txt"), encoding="utf-8", errors="replace").read()
    m = re.search(r"^GLSLANG_VALIDATOR:FILEPATH=(.+)$", cache, re.M)
    return m.group(1).strip() if m and os.path.isfile(m.group(1).strip()) else None


def glsl_check(ctx):
    """Compiles the lab stage's GPU kernel with the student's file in place, sealed (the work
    copy read-only, the references hidden, the SPIR-V thrown away); its Result, or None when the
    build has no glslangValidator."""
    build, src, box = ctx["build"], ctx["src"], ctx["sandbox"]
    tool = glslang(build)
    if tool is None:
        return None
    shader = os.path.join(build, LAB_STAGE[ctx["args"].lab], "kernel.comp")
    cmd = [tool, "--quiet", "-V", "--target-env", "vulkan1.1", f"-I{src}", f"-I{os.path.join(build, 'generated')}",
           "-o", "/dev/null", shader]
    return box.run(cmd, build, [], [src, build], box.hidden_in_build, BUILD_LIMITS, GLSL_TIMEOUT)
