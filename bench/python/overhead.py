#!/usr/bin/python3
"""The Python module's call overhead against the C++ programs on the same
work, and when a label array is copied (bench/README.md, "Python module").

  homogenize: the 64^3 sphere cell (cases/cells/sphere.toml --resolution 64):
    `homogenize --json` (its wall_s: the solve) against lamina.homogenize in
    this process (perf_counter around the call, and the call's own wall_s).
  membrane: the 100 x 100 benchmark sheet (bench/membrane/bench.toml, 200
    steps): `membrane run --json` (summary wall_s) against
    lamina.membrane.run (around the call, outputs read back as arrays).
  copy: a 128^3 int32 C-order label array, np.shares_memory with
    cell.phase_map(), then each dtype and order: copied or not, against
    what the contract (python/lamina/__init__.pyi) says.

Runs alternate: program, Python, program, Python... after one warm-up of
each (not counted: FFTW planning, the page cache). Prints best and median
of each and the overhead (Python - program) / program of both.

Usage: overhead.py [--build BUILD] [--repeats N] [--threads N]
                   [--only homogenize,membrane,copy] [--json FILE]
Do not run it on a shared, loaded machine: it measures wall time.
"""
import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
SPHERE = ROOT / "cases" / "cells" / "sphere.toml"
SHEET = ROOT / "bench" / "membrane" / "bench.toml"


def program_json(command):
    """Runs a program with --json: its output parsed, and the process wall
    time (s)."""
    start = time.perf_counter()
    proc = subprocess.run([str(c) for c in command], capture_output=True, text=True)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        sys.exit(f"overhead.py: {' '.join(map(str, command))} exited {proc.returncode}:\n"
                 f"{proc.stderr}")
    try:  # membrane: one JSON document; homogenize: one JSON line per entry
        return json.loads(proc.stdout), wall
    except json.JSONDecodeError:
        return json.loads(proc.stdout.strip().splitlines()[-1]), wall


def timed(call):
    """call() and its wall time (s)."""
    start = time.perf_counter()
    value = call()
    return value, time.perf_counter() - start


def summary(name, samples):
    """best, median of a list of seconds, printed."""
    best, median = min(samples), statistics.median(samples)
    print(f"  {name:44s} best {best:9.4f} s   median {median:9.4f} s   ({len(samples)} runs)")
    return {"best": best, "median": median, "runs": samples}


def overhead(name, python, program):
    """(Python - program) / program of the medians and of the bests, in %."""
    out = {k: 100 * (python[k] - program[k]) / program[k] for k in ("median", "best")}
    print(f"  overhead of {name}: median {out['median']:+.2f} %, best {out['best']:+.2f} %")
    return out


def alternate(repeats, program_run, python_run):
    """Warm-up of each, then `repeats` alternating pairs; the samples."""
    program_run(), python_run()
    samples = {}
    for _ in range(repeats):
        for run in (program_run, python_run):
            for key, value in run().items():
                samples.setdefault(key, []).append(value)
    return samples


def bench_homogenize(lamina, bin_dir, work, args):
    print(f"homogenize: {SPHERE.name} at 64^3, {args.threads} thread(s)")
    library = work / "library.toml"
    command = [bin_dir / "homogenize", SPHERE, "--resolution", "64", "--name", "bench-64",
               "--overwrite", "--library", library, "--threads", args.threads, "--json",
               "--quiet"]

    def program_run():
        out, wall = program_json(command)
        return {"program solve (its JSON wall_s)": out["wall_s"], "program process": wall}

    def python_run():
        cell, build = timed(lambda: lamina.Cell.from_file(SPHERE, set={"cell.resolution": 64}))
        result, call = timed(lambda: lamina.homogenize(cell, threads=args.threads or None))
        return {"lamina.homogenize call": call, "lamina.homogenize's own wall_s": result.wall_s,
                "lamina.Cell.from_file": build}

    samples = alternate(args.repeats, program_run, python_run)
    stats = {k: summary(k, v) for k, v in samples.items()}
    return dict(stats, overhead=overhead("the call against the program's solve",
                                         stats["lamina.homogenize call"],
                                         stats["program solve (its JSON wall_s)"]),
                overhead_in_process=overhead("the call against its own wall_s",
                                             stats["lamina.homogenize call"],
                                             stats["lamina.homogenize's own wall_s"]))


def bench_membrane(lamina, bin_dir, work, args):
    print(f"membrane: {SHEET.name} (100 x 100, 200 steps), {args.threads} thread(s)")
    command = [bin_dir / "membrane", "run", SHEET, "--out", work / "program-run",
               "--threads", args.threads, "--json", "--quiet"]

    def program_run():
        out, wall = program_json(command)
        return {"program run (its summary wall_s)": out["wall_s"], "program process": wall}

    def python_run():
        result, call = timed(lambda: lamina.membrane.run(SHEET, out=work / "python-run",
                                                         threads=args.threads or None))
        return {"lamina.membrane.run call": call,
                "lamina.membrane.run's summary wall_s": result.summary["wall_s"]}

    samples = alternate(args.repeats, program_run, python_run)
    stats = {k: summary(k, v) for k, v in samples.items()}
    return dict(stats, overhead=overhead("the call against the program's run",
                                         stats["lamina.membrane.run call"],
                                         stats["program run (its summary wall_s)"]),
                overhead_in_process=overhead("the call against its own wall_s",
                                             stats["lamina.membrane.run call"],
                                             stats["lamina.membrane.run's summary wall_s"]))


def copy_check(lamina, np):
    """Which label arrays Cell.from_array uses without a copy (128^3)."""
    n = 128
    x = (np.arange(n) + 0.5) / n - 0.5
    inside = (x[:, None, None] ** 2 + x[None, :, None] ** 2 + x[None, None, :] ** 2) < 0.3 ** 2
    phases = {0: {"name": "matrix", "law": "isotropic", "E": 156e6, "nu": 0.494,
                  "density": 1100.0},
              1: {"name": "sphere", "law": "isotropic", "E": 890e6, "nu": 0.491,
                  "density": 1100.0}}
    base = np.ascontiguousarray(inside, dtype=np.int32)
    cases = {f"{np.dtype(t).name}, {o} order": np.asarray(base, dtype=t, order=o)
             for t in (np.int8, np.uint8, np.int16, np.int32, np.uint32, np.int64)
             for o in ("C", "F")}
    wide = np.zeros((n, n, 2 * n), dtype=np.int32)
    wide[:, :, ::2] = base
    cases["int32, strided view (every 2nd z)"] = wide[:, :, ::2]
    shifted = {7: phases[0], 9: phases[1]}
    print(f"copy: a {n}^3 label array (the contract: no copy for int32, C order, ids 0..P-1)")
    rows = []
    for name, labels in list(cases.items()) + [("int32, C order, ids 7 and 9", None)]:
        if labels is None:
            labels, table = 7 + 2 * base, shifted
        else:
            table = phases
        cell = lamina.Cell.from_array(labels, table, size=100e-6)
        shares = bool(np.shares_memory(labels, cell.phase_map()))
        expected = (labels.dtype == np.int32 and labels.flags.c_contiguous and table is phases)
        agree = shares == (not cell.copied) and shares == expected
        rows.append({"array": name, "copied": cell.copied, "shares_memory": shares,
                     "as the contract says": agree})
        print(f"  {name:36s} copied {str(cell.copied):5s}  shares memory {str(shares):5s}"
              f"  {'as documented' if agree else 'DIFFERS from the contract'}")
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=ROOT / "build", type=pathlib.Path,
                        help="build folder: its bin/ programs and python/ module (default build)")
    parser.add_argument("--repeats", type=int, default=5, help="alternating pairs (default 5)")
    parser.add_argument("--threads", type=int, default=1,
                        help="of both sides (default 1; 0: each side's automatic choice)")
    parser.add_argument("--only", default="homogenize,membrane,copy",
                        help="comma-separated: homogenize, membrane, copy")
    parser.add_argument("--json", type=pathlib.Path, help="write the figures here too")
    args = parser.parse_args()
    only = set(args.only.split(","))
    if not only <= {"homogenize", "membrane", "copy"} or args.repeats < 1 or args.threads < 0:
        parser.error("--only takes homogenize, membrane, copy; --repeats >= 1; --threads >= 0")
    build = args.build.resolve()
    bin_dir = build / "bin"
    for name in ({"homogenize", "membrane"} & only):
        if not (bin_dir / name).is_file():
            sys.exit(f"overhead.py: no {bin_dir / name} (cmake --build {build} --target {name})")
    sys.path.insert(0, str(build / "python"))
    try:
        import numpy as np
        import lamina
    except ImportError as e:
        sys.exit(f"overhead.py: {e} (build the target lamina_python; run with /usr/bin/python3)")
    print(f"lamina {lamina.__version__} from {pathlib.Path(lamina.__file__).parent}")

    figures = {"threads": args.threads, "repeats": args.repeats}
    with tempfile.TemporaryDirectory(prefix="lamina-overhead-") as tmp:
        work = pathlib.Path(tmp)
        os.environ["LAMINA_LIBRARY"] = str(work / "library.toml")
        if "homogenize" in only:
            figures["homogenize"] = bench_homogenize(lamina, bin_dir, work, args)
        if "membrane" in only:
            figures["membrane"] = bench_membrane(lamina, bin_dir, work, args)
        if "copy" in only:
            figures["copy"] = copy_check(lamina, np)
    if args.json:
        args.json.write_text(json.dumps(figures, indent=1) + "\n")
        print("wrote", args.json)


if __name__ == "__main__":
    main()
