#!/usr/bin/env python3
"""Issue-3 force-loop goals in one command: every model x layout x precision x {1, 2} threads on
the ~10^5 and 10^6 simple-cubic cubes (delta = 3.015 dx), run by bench_forces in N interleaved
rounds, medians over the rounds, printed as a Markdown table next to the goal of each row; and in
the same rounds LAMMPS peri/pmb and peri/lps side by side with pdk's PMB and LPS steps on every
layout (bench/lammps/in.peri_bench: the same cube, the same velocity-Verlet steps from rest, 1 and
2 MPI ranks against 1 and 2 threads), the ratio LAMMPS time / pdk time per layout.

  bench/goals.py [--build DIR] [--rounds N] [--repeat R] [--sides 46,100] [--quick]
                 [--lammps-side 46] [--lammps-steps 10] [--no-lammps] [--out FILE]

The table is printed and written to bench/results/goals-<date>-<host>.md (--out to choose).

Goals (ns per directed bond per core, 1 thread): PMB <= 1.3, LPS <= 2.6, correspondence
(Neo-Hooke, Silling C_s 0.1) <= 5.0 in double and <= 3.0 with float storage or on the lattice
(stencil) path; 2 threads >= 1.8x one; >= 50 % of the in-core bound (bench_forces' core%: the
loop's square roots, divisions and FP operations per bond times the time per operation measured
on this CPU, bench/bench_forces.c "in-core bound") or of the triad roofline (roof%); PMB and LPS
>= 10x LAMMPS on every layout. A row says "met" when its median is within the goal. Layout csr is
the general path with the reference bond lengths stored (the default); csrc recomputes them.

The machine is shared: the header records the host (CPU model, logical CPUs, vector ISA, caches:
the force loops' bounds differ between CPU kinds, bench/README.md), the load average before and
after, and the triad bandwidth bench_forces measures; compare rows of one run, and read absolute
numbers with the load. --quick: one round, repeat 3, the 97k cube only (a smoke run, minutes).
Standard library only; bench_forces prints whitespace columns (its header line names them)."""
import argparse
import datetime
import os
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile

GOAL = {"pmb": 1.3, "lps": 2.6}
SPEEDUP_GOAL = 1.8
LAMMPS_GOAL = 10.0
CORE_GOAL = 50.0
HERE = os.path.dirname(os.path.abspath(__file__))


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
    try:  # lscpu's totals (per instance count in brackets)
        out = subprocess.run(["lscpu"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                             text=True, env=dict(os.environ, LC_ALL="C")).stdout
        for line in out.splitlines():
            key, _, val = line.partition(":")
            if key.strip() in ("L1d cache", "L1i cache", "L2 cache", "L3 cache"):
                caches.append("%s %s" % (key.strip().replace(" cache", ""), " ".join(val.split())))
    except OSError:
        pass
    if caches:
        return "%s, %d logical CPUs, %s, caches (lscpu): %s" % (
            model, os.cpu_count() or 0, isa, ", ".join(caches))
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
        if line.startswith("# in-core:"):
            INCORE.append(line[len("# in-core:"):].strip())
            continue
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


INCORE = []


def lammps_step(style, side, steps, ranks, work):
    """LAMMPS seconds per step (loop time / steps) of bench/lammps/in.peri_bench."""
    log = os.path.join(work, "lmp.%s.%s.np%d.log" % (style, side, ranks))
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = ["mpirun", "-np", str(ranks), "lmp", "-in", os.path.join(HERE, "lammps", "in.peri_bench"),
           "-var", "style", style, "-var", "L", str(side), "-var", "steps", str(steps), "-log", log,
           "-screen", "none"]
    out = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=work,
                         env=env)
    if out.returncode != 0:
        sys.stderr.write("goals.py: %s failed:\n%s" % (" ".join(cmd), out.stderr))
        sys.exit(1)
    for line in open(log):
        if line.startswith("Loop time of"):
            return float(line.split()[3]) / steps
    sys.exit("goals.py: no loop time in %s" % log)


def fmt(x, f="%.2f"):
    return f % x if x is not None else ""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--sides", default="46,100")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--lammps-side", type=int, default=46)
    ap.add_argument("--lammps-steps", type=int, default=10)
    ap.add_argument("--no-lammps", action="store_true")
    ap.add_argument("--out", default=None)
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
                     "--layout", "csrc", "--layout", "sell", "--layout", "stencil"] + common)
        runs.append([exe, "--side", s, "--model", "corr", "--law", "neo_hooke", "--stab",
                     "silling", "--layout", "csr", "--layout", "stencil"] + common)
    load0 = open("/proc/loadavg").read().split()[:3]
    t0 = datetime.datetime.now(datetime.timezone.utc)
    lammps = not a.no_lammps and shutil.which("lmp") and shutil.which("mpirun")
    if not a.no_lammps and not lammps:
        sys.stderr.write("goals.py: lmp or mpirun not found: no LAMMPS side by side "
                         "(apt-get install lammps)\n")
    work = tempfile.mkdtemp(prefix="pdk-goals-")
    lmp_t, pdk_t = {}, {}
    samples, triads = {}, {1: [], 2: []}
    core = {}
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
                if r.get("core%", "-") != "-":
                    core.setdefault(key, []).append(float(r["core%"]))
                core.setdefault(("roof",) + key, []).append(float(r["roof%"]))
        if lammps:
            for style in ("pmb", "lps"):
                cmd = [exe, "--side", str(a.lammps_side), "--model", style, "--layout", "csr",
                       "--layout", "csrc", "--layout", "sell", "--layout", "stencil", "--threads",
                       "1", "--threads", "2", "--steps", str(a.lammps_steps), "--triad-mib", "64"]
                sys.stderr.write("goals.py: round %d/%d: %s steps beside LAMMPS\n"
                                 % (rnd + 1, a.rounds, style))
                rows, _ = run(cmd)
                for r in rows:
                    pdk_t.setdefault((style, r["layout"], int(r["thr"])), []).append(
                        float(r["s/step"]))
                    lmp_n = int(r["bonds"])
                for p in (1, 2):
                    lmp_t.setdefault((style, p), []).append(
                        lammps_step(style, a.lammps_side, a.lammps_steps, p, work))
                    lmp_t.setdefault(("bonds", style), [lmp_n])
    load1 = open("/proc/loadavg").read().split()[:3]
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                                text=True, cwd=os.path.dirname(os.path.abspath(__file__))
                                ).stdout.strip()
    except OSError:
        commit = "?"
    shutil.rmtree(work, ignore_errors=True)
    out_lines = []

    def emit(line=""):
        print(line)
        out_lines.append(line)

    med = {k: statistics.median(x[0] for x in v) for k, v in samples.items()}
    medcore = {k: statistics.median(v) for k, v in core.items()}
    medcpu = {k: statistics.median(x[1] for x in v) for k, v in samples.items()}
    emit("Force-loop goals, %s UTC, commit %s, %d round(s) x median of %d passes; load average "
          "%s before, %s after; triad %.1f GB/s (1 thread), %.1f GB/s (2 threads), medians."
          % (t0.strftime("%Y-%m-%d %H:%M"), commit, a.rounds, a.repeat, " ".join(load0),
             " ".join(load1), statistics.median(triads[1] or [0]),
             statistics.median(triads[2] or [0])))
    emit()
    emit("Host: %s (%s)." % (host(), socket.gethostname()))
    if INCORE:
        emit()
        emit("pdk dispatches: %s (first round; in-core bound: "
             "bench/bench_forces.c)." % INCORE[0])
    emit()
    emit("| model | layout | storage | particles | ns/bond 1 thr | cpu ns/bond | goal | "
         "verdict | core % | roof % | ns/bond/core 2 thr | speed-up | ≥ 1.8 |")
    emit("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
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
        cp = medcore.get(key)
        rp = medcore.get(("roof",) + key)
        emit("| %s | %s | %s | %d | %.2f | %.2f | ≤ %.1f | %s | %s | %s | %s | %s | %s |" % (
            model, layout, prec, n, ns1, medcpu[key], goal, "met" if ok else "**missed**",
            fmt(cp, "%.0f"), fmt(rp, "%.0f"),
            "%.2f" % ns2 if ns2 else "", "%.2f" % sp if sp else "",
            "" if sp is None else ("yes" if sp >= SPEEDUP_GOAL else "**no**")))
    emit()
    emit("%d rows within their goal, %d not. core %%: the share of the in-core bound the loop "
         "reaches (CPU time; 3-D, the modelled loops only), roof %%: of the triad bandwidth (goal: "
         "≥ %.0f %% of one of them)." % (met, missed, CORE_GOAL))
    if lmp_t:
        emit()
        emit("LAMMPS side by side: %d particles, %d velocity-Verlet steps from rest, seconds per "
             "step, medians of the rounds; ratio = LAMMPS time / pdk time (goal ≥ %.0f):"
             % (a.lammps_side ** 3, a.lammps_steps, LAMMPS_GOAL))
        emit()
        emit("| style | P | LAMMPS s/step | LAMMPS ns/bond/core | pdk layout | pdk s/step | "
             "ratio | ≥ 10 |")
        emit("|---|---|---|---|---|---|---|---|")
        for style in ("pmb", "lps"):
            nb = lmp_t.get(("bonds", style), [0])[0]
            for p in (1, 2):
                lt = statistics.median(lmp_t[(style, p)])
                for layout in ("csr", "csrc", "sell", "stencil"):
                    v = pdk_t.get((style, layout, p))
                    if not v:
                        continue
                    pt = statistics.median(v)
                    emit("| peri/%s | %d | %.4f | %.1f | %s | %.5f | %.1f | %s |" % (
                        style, p, lt, lt * p / nb * 1e9 if nb else 0, layout, pt, lt / pt,
                        "yes" if lt / pt >= LAMMPS_GOAL else "**no**"))
    out = a.out
    if out is None:
        os.makedirs(os.path.join(HERE, "results"), exist_ok=True)
        out = os.path.join(HERE, "results", "goals-%s-%s.md" % (t0.strftime("%Y-%m-%d"),
                                                                socket.gethostname()))
    with open(out, "w") as fh:
        fh.write("\n".join(out_lines) + "\n")
    sys.stderr.write("goals.py: wrote %s\n" % out)


if __name__ == "__main__":
    main()
