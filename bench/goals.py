#!/usr/bin/env python3
"""Issue-3 force-loop goals in one command: every model x layout x precision x {1, 2} threads on
the ~10^5 and 10^6 simple-cubic cubes (delta = 3.015 dx), run by bench_forces in N interleaved
rounds, medians over the rounds, printed as a Markdown table next to the goal of each row.

  bench/goals.py [--build DIR] [--rounds N] [--repeat R] [--sides 46,100] [--quick]

Goals (ns per directed bond per core, 1 thread): PMB <= 1.3, LPS <= 2.6, correspondence
(Neo-Hooke, Silling C_s 0.1) <= 5.0 in double and <= 3.0 with float storage or on the lattice
(stencil) path; 2 threads >= 1.8x one. A row says "met" when its median is within the goal.

The machine is shared: the header records the host (CPU model, logical CPUs, vector ISA, caches:
the force loops' bounds differ between CPU kinds, bench/README.md), the load average before and
after, and the triad bandwidth bench_forces measures; compare rows of one run, and read absolute
numbers with the load. --quick: one round, repeat 3, the 97k cube only (a smoke run, minutes).
Standard library only; bench_forces prints whitespace columns (its header line names them)."""
import argparse
import datetime
import os
import statistics
import subprocess
import sys

GOAL = {"pmb": 1.3, "lps": 2.6}
SPEEDUP_GOAL = 1.8


def corr_goal(prec, layout):
    if layout == "stencil" or prec == "float":
        return 3.0
    return 5.0


def host():
    """One line naming the CPU: model, logical CPUs, widest vector ISA, cache sizes (Linux /proc
    and /sys; '?' where they are not readable)."""
    model, flags = "?", set()
    try:
        for line in open("/proc/cpuinfo"):
            key, _, val = line.partition(":")
            if key.strip() == "model name" and model == "?":
                model = " ".join(val.split())
            elif key.strip() == "flags" and not flags:
                flags = set(val.split())
    except OSError:
        pass
    isa = ("AVX-512" if "avx512f" in flags else "AVX2" if "avx2" in flags
           else "SSE2" if "sse2" in flags else "?")
    caches = []
    base = "/sys/devices/system/cpu/cpu0/cache"
    try:
        for idx in sorted(os.listdir(base)):
            d = os.path.join(base, idx)
            try:
                level = open(os.path.join(d, "level")).read().strip()
                kind = open(os.path.join(d, "type")).read().strip()
                size = open(os.path.join(d, "size")).read().strip()
            except OSError:
                continue
            tag = {"Data": "d", "Instruction": "i"}.get(kind, "")
            caches.append("L%s%s %s" % (level, tag, size))
    except OSError:
        pass
    return "%s, %d logical CPUs, %s, caches per core / shared: %s" % (
        model, os.cpu_count() or 0, isa, ", ".join(caches) or "?")


def run(cmd):
    """Rows of one bench_forces run: dicts keyed by the header's column names."""
    out = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if out.returncode != 0:
        sys.stderr.write("goals.py: %s failed (%d):\n%s" % (" ".join(cmd), out.returncode,
                                                             out.stderr))
        sys.exit(1)
    cols, rows, triad = None, [], []
    for line in out.stdout.splitlines():
        if line.startswith("# model"):
            cols = line[1:].split()
            continue
        if line.startswith("#") or not line.strip() or cols is None:
            continue
        f = line.split()
        if "(unsupported:" in line or len(f) != len(cols):
            continue
        r = dict(zip(cols, f))
        rows.append(r)
        triad.append((int(r["thr"]), float(r["triad"])))
    return rows, triad


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--sides", default="46,100")
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    if a.quick:
        a.rounds, a.repeat, a.sides = 1, 3, "46"
    exe = os.path.join(a.build, "bench", "bench_forces")
    if not os.access(exe, os.X_OK):
        sys.exit("goals.py: %s not found: build first (cmake --build %s)" % (exe, a.build))
    sides = [s for s in a.sides.split(",") if s]
    common = ["--precision", "double", "--precision", "float", "--threads", "1", "--threads",
              "2", "--repeat", str(a.repeat), "--triad-mib", "256"]
    runs = []
    for s in sides:
        runs.append([exe, "--side", s, "--model", "pmb", "--model", "lps", "--layout", "csr",
                     "--layout", "sell", "--layout", "stencil"] + common)
        runs.append([exe, "--side", s, "--model", "corr", "--law", "neo_hooke", "--stab",
                     "silling", "--layout", "csr", "--layout", "stencil"] + common)
    load0 = open("/proc/loadavg").read().split()[:3]
    t0 = datetime.datetime.now(datetime.timezone.utc)
    samples, triads = {}, {1: [], 2: []}
    for rnd in range(a.rounds):
        for cmd in runs:
            sys.stderr.write("goals.py: round %d/%d: %s\n" % (rnd + 1, a.rounds,
                                                             " ".join(cmd[1:5])))
            rows, triad = run(cmd)
            for thr, gbs in triad:
                triads.setdefault(thr, []).append(gbs)
            for r in rows:
                key = (r["model"], r["layout"], r["prec"], int(r["n"]), int(r["thr"]))
                samples.setdefault(key, []).append((float(r["ns/b/c"]), float(r["cpu_ns/b"])))
    load1 = open("/proc/loadavg").read().split()[:3]
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                                text=True, cwd=os.path.dirname(os.path.abspath(__file__))
                                ).stdout.strip()
    except OSError:
        commit = "?"
    med = {k: statistics.median(x[0] for x in v) for k, v in samples.items()}
    medcpu = {k: statistics.median(x[1] for x in v) for k, v in samples.items()}
    print("Force-loop goals, %s UTC, commit %s, %d round(s) x median of %d passes; load average "
          "%s before, %s after; triad %.1f GB/s (1 thread), %.1f GB/s (2 threads), medians."
          % (t0.strftime("%Y-%m-%d %H:%M"), commit, a.rounds, a.repeat, " ".join(load0),
             " ".join(load1), statistics.median(triads[1] or [0]),
             statistics.median(triads[2] or [0])))
    print()
    print("Host: %s." % host())
    print()
    print("| model | layout | storage | particles | ns/bond 1 thr | cpu ns/bond | goal | "
          "verdict | ns/bond/core 2 thr | speed-up | ≥ 1.8 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    met = missed = 0
    for key in sorted(med, key=lambda k: (k[0], k[3], k[1], k[2], k[4])):
        model, layout, prec, n, thr = key
        if thr != 1:
            continue
        ns1 = med[key]
        goal = corr_goal(prec, layout) if model == "corr" else GOAL.get(model)
        ok = goal is not None and ns1 <= goal
        met += ok
        missed += goal is not None and not ok
        k2 = (model, layout, prec, n, 2)
        ns2 = med.get(k2)
        sp = 2.0 * ns1 / ns2 if ns2 else None
        print("| %s | %s | %s | %d | %.2f | %.2f | ≤ %.1f | %s | %s | %s | %s |" % (
            model, layout, prec, n, ns1, medcpu[key], goal, "met" if ok else "**missed**",
            "%.2f" % ns2 if ns2 else "", "%.2f" % sp if sp else "",
            "" if sp is None else ("yes" if sp >= SPEEDUP_GOAL else "**no**")))
    print()
    print("%d rows within their goal, %d not." % (met, missed))


if __name__ == "__main__":
    main()
