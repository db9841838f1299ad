#!/usr/bin/env python3
"""The README's commands work as printed, from the repository root.

Collects every command the README prints: the lines of its ```sh blocks (a block is one shell session, so a
variable set on one line is seen by the next), inline code spans that start like a command (build/..., bash ...,
sh ..., nice ..., python3 ..., cases/..., tools/..., VAR=value ...), and `build/tools/cushion <job> --help` for
every job heading. Untagged blocks are synopses with UPPER-CASE placeholders: not run.

--static: only checks that no command calls `cushion` bare (it is not on the PATH; the README prints
build/tools/cushion). Otherwise also runs every cheap command in a scratch copy of the repository root
(cases/ and tools/ copied, build/ a link to the build folder) and requires exit 0; the expensive ones (EXPENSIVE
below, each with the reason) are listed, not run. A command found neither runnable nor listed fails the test,
so a new README command must be cheap or named here.

Usage: check_readme_commands.py SOURCE_DIR BUILD_DIR [--static]
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

# Printed commands not run here (prefix match), with why.
EXPENSIVE = {
    "bash tools/quickstart.sh": "installs packages and builds",
    "bash tools/test.sh": "builds and runs the whole suite",
    "bash tools/fuzz.sh": "fuzzes for minutes per reader",
    "python3 tools/check_layers.py": "configures a CMake tree; run by the ctest Layers.IncludesFollowTheTargetGraph",
    "OPENBLAS_NUM_THREADS=1 bash tools/bench_cube.sh": "benchmark, minutes",
    "build/tests/bench_solver": "benchmark (and N is a placeholder)",
    "bash tools/bench_linear.sh": "benchmark, up to about 1 M dofs; needs a build with PETSc",
    "bash tools/bench_indentation_solvers.sh": "benchmark, about 20 min",
    "BENCH_SOLVER=petsc bash tools/bench_cube.sh": "benchmark, about 1 h at 1 M dofs",
    "bash tools/bench_diagnose.sh": "benchmark, hours",
    "bash tools/calculix_indentation.sh": "needs calculix-ccx, minutes",
    "build/tools/cushion run cases/sitbar_quasistatic/case.json": "about 2 min on 2 cores (the case runs shortened in ctest -L cases)",
    "bash cases/sitbar_quasistatic/plot.sh out_sitbar": "needs the 2 min SIT-BAR run above",
    "build/tools/cushion run cases/sitbar_quasistatic/case_full.json": "full model, minutes",
    "nice bash cases/sitbar_quasistatic/mesh_convergence.sh": "3 meshes, about 12 min",
}

COMMAND_START = re.compile(r"^(build/|bash |sh |nice |python3 |cases/|tools/|[A-Z_]+=\S+ )")
PLACEHOLDER = re.compile(r"\b[A-Z][A-Z_]{2,}(\.json|\.csv)?\b|\[|<|\.\.\.")


def read_readme(source):
    with open(os.path.join(source, "README.md"), encoding="utf-8") as f:
        return f.read().split("\n")


def shell_lines(block):
    """Commands of a sh block: comments dropped, continuation lines joined."""
    out, pending = [], ""
    for line in block:
        line = re.sub(r"\s+#.*$", "", line).rstrip()
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        if line.endswith("\\"):
            pending += line[:-1] + " "
            continue
        out.append(pending + line)
        pending = ""
    return out


def collect(lines):
    """(sessions, synopses, inline, jobs): sh blocks as lists of commands, synopsis lines, inline commands, job names."""
    sessions, synopses, inline, jobs = [], [], [], []
    fence, block = None, []
    for line in lines:
        if line.startswith("```"):
            if fence is None:
                fence, block = line[3:].strip(), []
            else:
                if fence == "sh":
                    sessions.append(shell_lines(block))
                elif fence == "":
                    synopses += [l for l in block if l.strip() and not l.startswith(" ")]
                fence = None
            continue
        if fence is not None:
            block.append(line)
            continue
        if re.match(r"^### \d+\. ", line):
            jobs += re.findall(r"`cushion (\w+)`", line)
        if line.startswith("#"):
            continue  # headings name jobs, they are not commands
        for span in re.findall(r"`([^`]+)`", line):
            if " " in span and (COMMAND_START.match(span) or span.startswith("cushion ")):  # a bare path names a file
                inline.append(span)
    return sessions, synopses, inline, jobs


def bare_cushion(sessions, synopses, inline):
    """Commands that call `cushion` as a program (a name such as `cushion fit` alone is prose, not a command)."""
    bad = []
    for cmd in [c for s in sessions for c in s] + synopses + inline:
        for part in re.split(r";|&&|\|\|", cmd):
            words = part.split()
            if words and words[0] == "cushion" and len(words) > 2:
                bad.append(cmd)
    return bad


def expensive(cmd):
    for prefix, why in EXPENSIVE.items():
        if cmd.startswith(prefix):
            return why
    return None


def scratch_root(source, build):
    root = tempfile.mkdtemp(prefix="cushion_readme_")
    shutil.copytree(os.path.join(source, "cases"), os.path.join(root, "cases"))
    shutil.copytree(os.path.join(source, "tools"), os.path.join(root, "tools"))
    shutil.copy(os.path.join(source, "README.md"), root)
    os.symlink(os.path.abspath(build), os.path.join(root, "build"))
    return root


def run(script, root):
    start = time.time()
    env = dict(os.environ)
    if os.geteuid() == 0:  # CI runs as root; OpenMPI's mpirun refuses root unless told (README: Distributed runs)
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run(["bash", "-c", "set -e\n" + script], cwd=root, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=1200, env=env)
    return p.returncode, p.stdout, time.time() - start


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    source, build, static = sys.argv[1], sys.argv[2], "--static" in sys.argv[3:]
    sessions, synopses, inline, jobs = collect(read_readme(source))
    failures = [f"calls cushion bare (not on the PATH; print build/tools/cushion): {c}"
                for c in bare_cushion(sessions, synopses, inline)]
    failures += [f"synopsis does not start with build/tools/cushion: {s}" for s in synopses
                 if s.split()[0].startswith("cushion")]
    if len(jobs) < 5:
        failures.append(f"expected the job headings (### N. ...: `cushion JOB`), found {jobs}")
    if static:
        for f in failures:
            print("FAIL", f)
        for c in inline:
            print("inline:", c)
        print(f"{len(sessions)} sh blocks, {len(synopses)} synopsis lines, {len(inline)} inline commands, jobs {jobs}")
        return 1 if failures else 0

    root = scratch_root(source, build)
    todo = [(f"build/tools/cushion {job} --help", f"build/tools/cushion {job} --help") for job in jobs]
    for session in sessions:
        skipped = [c for c in session if expensive(c)]
        runnable = [c for c in session if not expensive(c)]
        for c in skipped:
            print(f"not run (expensive: {expensive(c)}): {c}")
        if runnable:
            todo.append((" ; ".join(runnable), "\n".join(runnable)))
    for cmd in [c for c in inline if COMMAND_START.match(c)]:  # `cushion fit` alone names a job
        if expensive(cmd):
            print(f"not run (expensive: {expensive(cmd)}): {cmd}")
        elif PLACEHOLDER.search(cmd.split(" ", 1)[1] if " " in cmd else ""):
            print(f"not run (placeholders): {cmd}")
        else:
            todo.append((cmd, cmd))
    for name, script in todo:
        rc, output, seconds = run(script, root)
        print(f"{'ok  ' if rc == 0 else 'FAIL'} exit {rc} in {seconds:.1f} s: {name}")
        if rc != 0:
            failures.append(f"exit {rc}: {name}\n{output[-3000:]}")
    shutil.rmtree(root, ignore_errors=True)
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
