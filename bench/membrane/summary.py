#!/usr/bin/python3
"""The membrane benchmark's targets from the figures of one run.sh run.

Reads run.sh's output folder: the `membrane run --json` outputs
cg-N-T.json (structured N x N, T threads) and cg-gmsh-T.json (the
unstructured square), and membrane_kernels' --json files
kernels-N-T.kernels.json and kernels-gmsh-T.kernels.json. Prints, for 1 and
2 threads:
- Newmark step, unstructured / structured: `membrane run`'s mean step, the
  structured mesh the largest N <= 300 of SIZES (target <= 1.5);
- CG iteration / floor: membrane_kernels' one CG solve divided by its
  iterations, against one product with K in 3x3 blocks on the same mesh,
  best wall (target <= 1.5); step / (CG iterations + 1) / floor beside it
  (the step's vector passes charged to the products: an upper bound);
- explicit fabric step, unstructured / structured (the largest N <= 300 of
  KERNEL_SIZES) and / floor on each mesh, best wall (targets <= 1.3, <= 2);
- 2-thread speed-up, 1-thread time / 2-thread time, of the Newmark step
  (`membrane run`'s mean step) and of the explicit fabric step (kernels'
  best wall) on each mesh (target >= 1.7).
A figure whose run is missing prints as '-'.

Usage: summary.py OUT_DIR "SIZES" "KERNEL_SIZES"
"""
import json
import os
import sys


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def largest_at_most_300(sizes):
    ns = [int(n) for n in sizes.split() if int(n) <= 300]
    return max(ns) if ns else None


class Figures:
    """The run's figures by mesh ('gmsh' or N) and threads."""

    def __init__(self, out, n_run, n_kernels):
        self.out, self.n_run, self.n_kernels = out, n_run, n_kernels

    def step(self, mesh, th):
        """`membrane run`'s mean Newmark step (ms)."""
        mesh = self.n_run if mesh == "structured" else mesh
        d = load(os.path.join(self.out, "cg-%s-%d.json" % (mesh, th))) if mesh else None
        return 1e3 * d["step_s"] if d else None

    def kernels(self, mesh, th):
        mesh = self.n_kernels if mesh == "structured" else mesh
        name = "kernels-%s-%d.kernels.json" % (mesh, th)
        return load(os.path.join(self.out, name)) if mesh else None

    def best(self, mesh, th, key):
        """membrane_kernels' best wall of @key (ms)."""
        k = self.kernels(mesh, th)
        return k["timings"][key]["best_ms"] if k and key in k["timings"] else None

    def ratio(self, mesh, th, key):
        k = self.kernels(mesh, th)
        return k["ratios"][key]["best"] if k and key in k["ratios"] else None


def quotient(a, b):
    return a / b if a is not None and b else None


def fmt(x, digits=2):
    return "-" if x is None else "%.*f" % (digits, x)


def verdict(values, target, at_least=False):
    if any(v is None for v in values):
        return "(target %s %g: incomplete)" % (">=" if at_least else "<=", target)
    ok = all(v >= target if at_least else v <= target for v in values)
    return "(target %s %g: %s)" % (">=" if at_least else "<=", target, "met" if ok else "NOT met")


def report(f):
    sn, kn = f.n_run, f.n_kernels
    print("--- targets, from this run (kernels: best wall per call; membrane run: mean step)")
    print("structured mesh: N = %s (membrane run), N = %s (kernels); unstructured: the gmsh square"
          % (sn if sn else "- (no N <= 300 in SIZES)",
             kn if kn else "- (no N <= 300 in KERNEL_SIZES)"))
    rows = []
    r = [quotient(f.step("gmsh", th), f.step("structured", th)) for th in (1, 2)]
    rows.append(("Newmark step, unstructured / structured",
                 "1 thread %s (%s / %s ms), 2 threads %s (%s / %s ms)" % (
                     fmt(r[0]), fmt(f.step("gmsh", 1), 1), fmt(f.step("structured", 1), 1),
                     fmt(r[1]), fmt(f.step("gmsh", 2), 1), fmt(f.step("structured", 2), 1)),
                 verdict(r, 1.5)))
    r = [f.ratio("gmsh", th, "cg_iteration/floor") for th in (1, 2)]
    u = [f.ratio("gmsh", th, "newmark_product/floor") for th in (1, 2)]
    rows.append(("CG iteration / floor, unstructured",
                 "1 thread %s, 2 threads %s (step / (its + 1) / floor: %s, %s)"
                 % (fmt(r[0]), fmt(r[1]), fmt(u[0]), fmt(u[1])), verdict(r, 1.5)))
    r = [quotient(f.best("gmsh", th, "fabric_step"), f.best("structured", th, "fabric_step"))
         for th in (1, 2)]
    rows.append(("explicit fabric step, unstructured / structured",
                 "1 thread %s, 2 threads %s" % (fmt(r[0]), fmt(r[1])), verdict(r, 1.3)))
    r = [f.ratio(m, th, "fabric_step/floor") for m in ("gmsh", "structured") for th in (1, 2)]
    rows.append(("explicit fabric step / floor",
                 "unstructured %s, %s; structured %s, %s (1, 2 threads)" % tuple(map(fmt, r)),
                 verdict(r[:2], 2)))
    s = [quotient(f.step(m, 1), f.step(m, 2)) for m in ("gmsh", "structured")]
    e = [quotient(f.best(m, 1, "fabric_step"), f.best(m, 2, "fabric_step"))
         for m in ("gmsh", "structured")]
    rows.append(("2 threads / 1, Newmark step",
                 "unstructured %s, structured %s" % (fmt(s[0]), fmt(s[1])), verdict(s, 1.7, True)))
    rows.append(("2 threads / 1, explicit fabric step",
                 "unstructured %s, structured %s" % (fmt(e[0]), fmt(e[1])), verdict(e, 1.7, True)))
    for what, figures, target in rows:
        print("%-48s %s  %s" % (what, figures, target))


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    out, sizes, kernel_sizes = sys.argv[1:]
    report(Figures(out, largest_at_most_300(sizes), largest_at_most_300(kernel_sizes)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
