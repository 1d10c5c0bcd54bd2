#!/usr/bin/env python3
"""bench/README.md's headline figures in one command: the force-loop goal table, pdk against
LAMMPS PERI, the family build, the ductile step against the elastic one and the static solvers,
each run with the arguments bench/README.md quotes, into one dated Markdown file.

  bench/headline.py [--build DIR] [--out FILE] [--quick] [--only NAME ...]

--build: a Release build (default ./build; configure it with -DCMAKE_BUILD_TYPE=Release).
--out: the Markdown file (default bench/results/headline-<date>-<host>.md); it is written under a
  .part name and renamed when every section has run, so an interrupted run leaves no file that
  looks complete.
--quick: smaller bodies and fewer repeats (minutes; a smoke run, not figures to quote).
--only: run these sections only (goals, lammps, families, ductile, static).

The header records the date, the commit (and whether the tree had changes), the host (CPU model,
logical CPUs, vector ISA, caches) and the load average before and after: the machine may be
shared, so compare rows of one run and read absolute numbers with the load. The LAMMPS section
runs only where `lmp` is installed (Debian package lammps) and says so otherwise. Each section
gives its command, its wall time and the program's own output (the goal table is Markdown
already). Standard library only."""
import argparse
import datetime
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from goals import host  # noqa: E402  (the same host line as the goal table)


def sections(build, quick):
    b = os.path.join(build, "bench")
    py = sys.executable
    if quick:
        return [
            ("goals", "Force loops: the goal table", [py, os.path.join(HERE, "goals.py"), "--build", build, "--quick"]),
            ("lammps", "Against LAMMPS PERI", ["bash", os.path.join(HERE, "lammps", "run_bench.sh"), "-b", build, "-s", "30", "-n", "5"]),
            ("families", "Family build", [os.path.join(b, "bench_families"), "--n", "50", "--repeat", "2", "--threads", "1", "--threads", "2"]),
            ("ductile", "Ductile step against the elastic one", [os.path.join(b, "bench_ductile"), "--side", "60", "--repeat", "2", "--steps", "5"]),
            ("static", "Static solvers", [os.path.join(b, "bench_static"), "--dim", "2", "--sizes", "65", "--method", "both"]),
        ]
    return [
        ("goals", "Force loops: the goal table", [py, os.path.join(HERE, "goals.py"), "--build", build, "--rounds", "3"]),
        ("lammps", "Against LAMMPS PERI", ["bash", os.path.join(HERE, "lammps", "run_bench.sh"), "-b", build, "-s", "46", "-n", "10"]),
        ("families", "Family build", [os.path.join(b, "bench_families"), "--n", "100", "--repeat", "5", "--threads", "1", "--threads", "2"]),
        ("ductile", "Ductile step against the elastic one", [os.path.join(b, "bench_ductile"), "--side", "140", "--repeat", "7", "--steps", "20"]),
        ("static", "Static solvers", [os.path.join(b, "bench_static"), "--dim", "2", "--sizes", "129,257", "--method", "both"]),
    ]


def git(*args):
    try:
        return subprocess.run(["git", "-C", SRC, *args], capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "?"


def load():
    try:
        return " ".join(open("/proc/loadavg").read().split()[:3])
    except OSError:
        return "?"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(SRC, "build"))
    ap.add_argument("--out")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--only", nargs="+", choices=["goals", "lammps", "families", "ductile", "static"])
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    if not os.path.isfile(os.path.join(build, "CMakeCache.txt")):
        sys.exit(f"headline.py: '{build}' is not a CMake build directory; configure one first:\n"
                 f"  cmake -S {SRC} -B {build} -DCMAKE_BUILD_TYPE=Release && cmake --build {build} -j2")
    cache = open(os.path.join(build, "CMakeCache.txt")).read()
    if "CMAKE_BUILD_TYPE:STRING=Release" not in cache:
        sys.exit(f"headline.py: '{build}' is not a Release build; figures from it would mislead "
                 f"(configure with -DCMAKE_BUILD_TYPE=Release)")
    subprocess.run(["cmake", "--build", build, "-j2"], check=True, stdout=subprocess.DEVNULL)
    today = datetime.datetime.now(datetime.timezone.utc)
    hostline = host()
    short = hostline.split(",")[0].split()[0].lower() if hostline else "host"
    out = a.out or os.path.join(HERE, "results", f"headline-{today:%Y-%m-%d}-{short}.md")
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    commit = git("rev-parse", "--short", "HEAD")
    dirty = " (with uncommitted changes)" if git("status", "--porcelain", "--untracked-files=no") else ""
    lines = [f"# Headline figures, {today:%Y-%m-%d %H:%M} UTC{' (quick: not figures to quote)' if a.quick else ''}",
             "",
             f"- command: `bench/headline.py{' --quick' if a.quick else ''}"
             f"{' --only ' + ' '.join(a.only) if a.only else ''}`",
             f"- commit: {commit}{dirty}",
             f"- host: {hostline}",
             f"- load average before: {load()}",
             ""]
    failed = []
    for name, title, cmd in sections(build, a.quick):
        if a.only and name not in a.only:
            continue
        lines += [f"## {title}", "", "`" + " ".join(os.path.relpath(c, SRC) if c.startswith(SRC) else c for c in cmd) + "`", ""]
        if name == "lammps" and not any(os.access(os.path.join(p, "lmp"), os.X_OK)
                                        for p in os.environ.get("PATH", "").split(os.pathsep)):
            lines += ["Not run: `lmp` is not installed on this host (`apt-get install lammps`).", ""]
            continue
        print(f"headline.py: {title} ...", file=sys.stderr, flush=True)
        t0 = time.time()
        r = subprocess.run(cmd, capture_output=True, text=True, cwd=SRC)
        wall = time.time() - t0
        status = "" if r.returncode == 0 else f", exit status {r.returncode}"
        if r.returncode != 0:
            failed.append(name)
        lines += [f"{wall:.0f} s wall{status}, load average after: {load()}", ""]
        body = r.stdout.rstrip()
        if name == "goals" and r.returncode == 0:
            lines += [body, ""]
        else:
            lines += ["```", body + ("\n" + r.stderr.rstrip() if r.returncode else ""), "```", ""]
    part = out + ".part"
    with open(part, "w") as f:
        f.write("\n".join(lines))
    os.replace(part, out)
    print(f"headline.py: wrote {os.path.relpath(out, os.getcwd())}", file=sys.stderr)
    if failed:
        sys.exit(f"headline.py: sections failed: {', '.join(failed)} (their output is in the file)")


if __name__ == "__main__":
    main()
