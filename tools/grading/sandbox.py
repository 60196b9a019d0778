"""The sealed run of tools/grade_lab.py (grading a class's lab submissions; tooling for teachers,
not a part of the article): every command that compiles or runs a student's code runs inside
bubblewrap (Debian's `bubblewrap`), as an unprivileged user, with the system read-only, the
work copy read-only less the reference solutions (and, for the tests, the held-back tests),
no network, a private /tmp, one writable folder, and limits on CPU time, memory, processes
and file size. Its output comes back over pipes that the grader reads up to a cap."""
import os
import re
import selectors
import shutil
import signal
import subprocess
import time

NOBODY = 65534  # the user a root grader runs the sandbox as (a user's grader runs it as itself)
MiB = 1 << 20


class Limits:
    """The limits of one sealed command (prlimit inside the sandbox, and the pipes' caps)."""

    def __init__(self, cpu_s, memory, processes, file_size, stdout_cap, stderr_cap):
        self.cpu_s, self.memory, self.processes, self.file_size = cpu_s, memory, processes, file_size
        self.stdout_cap, self.stderr_cap = stdout_cap, stderr_cap


def memory_limit():
    """Address space per process: 8 GiB, or 3/4 of the machine's memory when that is less."""
    try:
        total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError):
        total = 8 << 30
    return min(8 << 30, total * 3 // 4)


BUILD_LIMITS = Limits(cpu_s=1200, memory=memory_limit(), processes=512, file_size=2048 * MiB,
                      stdout_cap=16 * MiB, stderr_cap=16 * MiB)
TEST_LIMITS = Limits(cpu_s=1200, memory=memory_limit(), processes=256, file_size=64 * MiB,
                     stdout_cap=32 * MiB, stderr_cap=8 * MiB)
FOLDER_CAP = 256 * MiB  # what a submission's tests may leave in their writable folder


TIME = "/usr/bin/time"  # GNU time (Debian's `time`): the CPU seconds of a sealed command, when installed
CPU_MARK = "pt-grade-cpu-seconds"
CPU_LINE = re.compile(rb"(\n?Command (exited with non-zero status|terminated by signal) \d+)?\n?"
                      + CPU_MARK.encode() + rb" ([0-9.]+) ([0-9.]+)\n?$")


class Result:
    """How a command ended: return code (negative: the signal), timed out, which pipe went over
    its cap (None, 'stdout' or 'stderr'), the bytes read from each, the seconds it took."""

    def __init__(self):
        self.rc, self.timed_out, self.over_cap = None, False, None
        self.stdout, self.stderr, self.report, self.seconds = b"", b"", b"", 0.0
        self.cpu_seconds = 0.0  # user + system time of the command and what it waited for (GNU time)
        self.running_function = None  # what on_timeout found running, if anything
        self.running_test = None  # the test the program started last (grading/submission.py)


class Sandbox:
    """Builds and runs sealed commands. sealed=False (--unsealed) runs them bare, with the same
    limits and pipes."""

    def __init__(self, sealed, src, hidden_in_build, hidden_in_tests):
        self.sealed, self.src = sealed, src
        self.hidden_in_build, self.hidden_in_tests = hidden_in_build, hidden_in_tests  # {path: placeholder}
        self.as_nobody = sealed and os.geteuid() == 0
        self.cpu_seconds = 0.0  # the CPU seconds of every command run so far

    def owner_of_writable(self, path):
        """Makes path (a folder the sandbox writes) the sandbox user's."""
        if self.as_nobody:
            for root, dirs, files in os.walk(path):
                for name in [root] + [os.path.join(root, n) for n in dirs + files]:
                    os.lchown(name, NOBODY, NOBODY)

    def argv(self, cmd, cwd, writable, readonly, hidden, limits, env):
        """The command line that runs cmd in cwd sealed with limits: writable and readonly are
        folders bound at their own paths; hidden maps a path to the placeholder shown instead;
        env: the variables set besides PATH, HOME, TMPDIR and LANG."""
        # RLIMIT_NPROC counts the user's processes; a user's grader adds the ones it has already.
        processes = limits.processes if self.as_nobody else limits.processes + user_processes()
        limited = ["prlimit", f"--cpu={limits.cpu_s}", f"--as={limits.memory}", f"--fsize={limits.file_size}",
                   "--core=0", f"--nproc={processes}", "--"] + cmd
        if os.path.isfile(TIME):  # the command's CPU time on its stderr's last line (bwrap's
            limited = [TIME, "-f", CPU_MARK + " %U %S", "--"] + limited  # own wait does not pass it on)
        if not self.sealed:
            return limited
        if self.as_nobody:
            # bwrap binds as root (so a folder under /root can be bound), then the command drops
            # to nobody: no user namespace, a real uid whose processes RLIMIT_NPROC counts.
            argv = ["bwrap", "--unshare-ipc", "--unshare-pid", "--unshare-net", "--unshare-uts", "--unshare-cgroup-try",
                    "--cap-add", "CAP_SETUID", "--cap-add", "CAP_SETGID"]
            limited = ["setpriv", f"--reuid={NOBODY}", f"--regid={NOBODY}", "--clear-groups", "--inh-caps=-all",
                       "--no-new-privs", "--"] + limited
        else:
            argv = ["bwrap", "--unshare-all"]
        argv += ["--die-with-parent", "--new-session", "--ro-bind", "/usr", "/usr", "--ro-bind", "/etc", "/etc"]
        for link in ("bin", "lib", "lib64", "sbin"):
            target = os.path.join("/", link)
            if os.path.islink(target):
                argv += ["--symlink", os.readlink(target), target]
            elif os.path.isdir(target):
                argv += ["--ro-bind", target, target]
        argv += ["--proc", "/proc", "--dev", "/dev", "--perms", "1777", "--size", str(256 * MiB), "--tmpfs", "/tmp"]
        # The folders above the bound ones, made traversable (bwrap would copy their modes, and
        # nobody cannot pass a 0700 folder such as /root or a mkdtemp).
        bound = list(readonly) + list(writable)
        above = set()
        for path in bound:
            parent = os.path.dirname(path)
            while parent not in ("/", "") and not parent.startswith(("/usr", "/etc", "/proc", "/dev")):
                if not any(parent == b or parent.startswith(b + os.sep) for b in bound):
                    above.add(parent)
                parent = os.path.dirname(parent)
        for path in sorted(above, key=lambda p: p.count(os.sep)):
            argv += ["--perms", "0755", "--dir", path]
        for path in readonly:
            argv += ["--ro-bind", path, path]
        for path in writable:
            argv += ["--bind", path, path]
        for path, placeholder in sorted(hidden.items()):
            argv += ["--ro-bind", placeholder, path]
        argv += ["--chdir", cwd, "--clearenv"]
        for k, v in sorted({"PATH": "/usr/bin:/bin", "HOME": cwd, "TMPDIR": "/tmp", "LANG": "C.UTF-8", **env}.items()):
            argv += ["--setenv", k, v]
        return argv + ["--"] + limited

    def run(self, cmd, cwd, writable, readonly, hidden, limits, timeout, env=None, report=False, on_timeout=None):
        """Runs cmd sealed; returns its Result. The whole process tree is killed after timeout
        seconds (on_timeout(pid) first says what it was running), or as soon as one of its
        pipes goes over its cap. report: '{report}' in cmd becomes a pipe of the grader's own
        (/dev/fd/N), read into Result.report: the sandbox cannot write it but through that fd."""
        pipe = os.pipe() if report else None
        if pipe:
            if self.as_nobody:  # opening /dev/fd/N opens the pipe anew, which checks its owner
                os.fchown(pipe[1], NOBODY, NOBODY)
            cmd = [c.replace("{report}", f"/dev/fd/{pipe[1]}") for c in cmd]
        argv = self.argv(cmd, cwd, writable, readonly, hidden, limits, env or {})
        full_env = None if self.sealed else {**os.environ, **(env or {})}
        r = run_capped(argv, "/" if self.sealed else cwd, limits, timeout, full_env, pipe, on_timeout)
        self.cpu_seconds += r.cpu_seconds
        return r


def user_processes():
    """How many processes this user has now (for RLIMIT_NPROC, which counts them all)."""
    uid, count = os.getuid(), 0
    for pid in os.listdir("/proc"):
        if pid.isdigit():
            try:
                if os.stat(os.path.join("/proc", pid)).st_uid == uid:
                    count += 1
            except OSError:
                pass
    return count


def run_capped(argv, cwd, limits, timeout, env, pipe=None, on_timeout=None):
    """Runs argv in a session of its own with stdout, stderr (and the report pipe) read, each
    kept up to its cap; kills the session (and with it the sandbox) at the deadline or the
    first cap."""
    r, start = Result(), time.monotonic()
    p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL,
                         cwd=cwd, env=env, start_new_session=True, pass_fds=(pipe[1],) if pipe else ())
    caps = {p.stdout: ("stdout", limits.stdout_cap), p.stderr: ("stderr", limits.stderr_cap)}
    report = None
    if pipe:
        os.close(pipe[1])
        report = os.fdopen(pipe[0], "rb", buffering=0)
        caps[report] = ("report", limits.stdout_cap)
    data = {f: bytearray() for f in caps}
    sel = selectors.DefaultSelector()
    for f in caps:
        sel.register(f, selectors.EVENT_READ)
    deadline = start + timeout
    try:
        while sel.get_map() and r.over_cap is None:
            left = deadline - time.monotonic()
            if left <= 0:
                r.timed_out = True
                if on_timeout:
                    r.running_function = on_timeout(p.pid)
                break
            for key, _ in sel.select(timeout=min(left, 1.0)):
                chunk = os.read(key.fileobj.fileno(), 1 << 16)
                if not chunk:
                    sel.unregister(key.fileobj)
                    continue
                buf, (name, cap) = data[key.fileobj], caps[key.fileobj]
                room = cap - len(buf)
                buf += chunk[:room]
                if len(chunk) > room:
                    r.over_cap = name
                    break
        if not r.timed_out and r.over_cap is None:
            p.wait(timeout=max(0.1, deadline - time.monotonic()))
    except subprocess.TimeoutExpired:
        r.timed_out = True
    finally:
        kill_session(p)
        sel.close()
        for f in caps:
            f.close()
    r.rc = p.returncode
    r.stdout, r.stderr = bytes(data[p.stdout]), bytes(data[p.stderr])
    r.report = bytes(data[report]) if report else b""
    r.seconds = time.monotonic() - start
    m = CPU_LINE.search(r.stderr)
    if m:  # GNU time's line, the last of stderr: the command's CPU seconds, taken off its output
        r.cpu_seconds, r.stderr = float(m.group(3)) + float(m.group(4)), r.stderr[:m.start()]
    return r


def kill_session(p):
    """Kills p's session (bwrap dies, and with it every process of its namespace) and reaps p."""
    try:
        os.killpg(p.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    p.wait()


def probe():
    """None when a sealed run works here, else one sentence saying why not."""
    if shutil.which("bwrap") is None:
        return "bubblewrap (bwrap) is not installed: apt-get install bubblewrap"
    for tool in ("prlimit", "setpriv"):
        if shutil.which(tool) is None:
            return f"{tool} is missing (util-linux)"
    box = Sandbox(True, "/", {}, {})
    limits = Limits(10, memory_limit(), 64, MiB, MiB, MiB)
    r = box.run(["true"], "/tmp", [], [], {}, limits, 30)
    if r.rc != 0:
        why = " ".join(r.stderr.decode(errors="replace").split())[:200]
        return (f"bubblewrap cannot start a sandbox here ({why or 'exit ' + str(r.rc)}): "
                "user namespaces may be off (sysctl kernel.unprivileged_userns_clone=1, or user.max_user_namespaces)")
    return None
