"""The set-up's use of a compiler cache, for tools/grade_lab.py --compiler-cache (grading a class's
lab submissions; tooling for teachers, not a part of the article). A lab build compiles the
libraries common/, cpu/ and gpu/ and the film's tools with the Release build's command lines
(cmake/Labs.cmake gives the lab's options to the stages, the tests and the bench only), so
where ccache holds that build's objects (./tutorial test builds with ccache, CCACHE_BASEDIR the
checkout) and the work copy lies inside the checkout, its build folder a child of the copy as
the checkout's build folder is of the checkout (work_build.work_paths), the set-up takes them
from the cache instead of compiling them again: about half of a lab's set-up on 2 cores
(docs/labs/teachers.md). The cache is only read: bound read-only into the set-up's sandbox,
ccache in read-only mode without statistics, its temporary files in the build folder. A
submission's build never sees it (CCACHE_DISABLE), so no student's code can reach it."""
import os
import shutil
import subprocess

# Read from the user's ccache and handed into the sandbox, whose environment is cleared.
PASSED = {"cache_dir": "CCACHE_DIR", "base_dir": "CCACHE_BASEDIR", "sloppiness": "CCACHE_SLOPPINESS",
          "compiler_check": "CCACHE_COMPILERCHECK"}
SUBMISSION_ENV = {"CCACHE_DISABLE": "1"}  # a submission's build (and a set-up without it): the compiler itself


class CompilerCache:
    """What the set-up's configure and builds add when the cache is used (enabled), and what a
    submission's build adds (the cache off)."""

    def __init__(self, settings=None, why_not=None):
        self.settings, self.why_not = settings or {}, why_not

    @property
    def enabled(self):
        return bool(self.settings)

    def configure_args(self):
        """The launcher for the set-up's configure (none: a build configured with it before forgets it)."""
        return ["-DCMAKE_CXX_COMPILER_LAUNCHER=" + ("ccache" if self.enabled else "")]

    def setup_env(self, build):
        """The set-up's environment: the user's cache read-only, temporary files in build."""
        if not self.enabled:
            return dict(SUBMISSION_ENV)
        env = {PASSED[k]: v for k, v in self.settings.items() if v}
        env.update({"CCACHE_READONLY": "1", "CCACHE_NOSTATS": "1", "CCACHE_TEMPDIR": os.path.join(build, "ccache-tmp")})
        return env

    def readonly(self):
        """The folders the set-up's sandbox sees read-only besides the work copy: the cache."""
        return [self.settings["cache_dir"]] if self.enabled else []


def compiler_cache(wanted):
    """The CompilerCache of this run: the user's ccache when wanted and usable, else off (with
    why_not, one sentence for the grader's log)."""
    if not wanted:
        return CompilerCache()
    ccache = shutil.which("ccache")
    if ccache is None:
        return CompilerCache(why_not="ccache is not installed: the set-up compiles everything")
    settings = {}
    for key in PASSED:
        r = subprocess.run([ccache, "--get-config", key], capture_output=True, text=True)
        if r.returncode != 0:
            return CompilerCache(why_not=f"ccache --get-config {key} failed: the set-up compiles everything")
        settings[key] = r.stdout.strip()
    if not os.path.isdir(settings["cache_dir"]):
        return CompilerCache(why_not=f"ccache's cache {settings['cache_dir']} does not exist yet: the set-up compiles everything")
    settings["cache_dir"] = os.path.realpath(settings["cache_dir"])
    return CompilerCache(settings)
