#!/usr/bin/python3
"""Pictures of the blast-loaded roof (drag paper, section 5), with and without drag.

Usage: /usr/bin/python3 scripts/plot_roof.py OUT_DIR [--image PATH]

OUT_DIR is the output folder of `membrane run cases/membrane/blast-roof.toml`
(compare_without_drag = true): OUT_DIR/with-drag and OUT_DIR/without-drag
each hold <case>.h5 (/mesh/geometry, /steps/<k>/displacement with a `time`
attribute), probes.csv (the probe `centre`) and reactions.csv (columns
<set>_Rx, <set>_Ry, <set>_Rz). Writes into OUT_DIR:

  roof-side.png     side view of the roof at its peak, both runs (paper Fig. 12)
  roof-history.png  centre vertical displacement and total support reaction
                    (magnitude of the sum of all reactions) against time (Fig. 13)

--image PATH also writes a combined picture (for the README) to PATH
(docs/images/blast-roof.png: --image docs/images/blast-roof.png). Prints
"wrote PATH" for each picture.
"""
import argparse
import json
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

RUNS = (("without-drag", "without drag", "tab:red"), ("with-drag", "with drag", "tab:blue"))


def read_csv(path):
    with open(path) as fh:
        rows = list(csv.reader(fh))
    if len(rows) < 2:
        sys.exit(f"plot_roof: {path} has no data rows")
    return rows[0], np.array(rows[1:], dtype=float)


def centre_history(run_dir):
    header, data = read_csv(os.path.join(run_dir, "probes.csv"))
    if "centre_uz" not in header:
        sys.exit(f"plot_roof: {run_dir}/probes.csv has no centre_uz column")
    return data[:, 0], data[:, header.index("centre_uz")]


def total_reaction(run_dir):
    header, data = read_csv(os.path.join(run_dir, "reactions.csv"))
    total = np.zeros((data.shape[0], 3))
    for j, name in enumerate(header):
        for c, suffix in enumerate(("_Rx", "_Ry", "_Rz")):
            if name.endswith(suffix):
                total[:, c] += data[:, j]
    return data[:, 0], np.linalg.norm(total, axis=1)


def shape_at_peak(run_dir):
    """Nodes (undeformed, deformed) at the stored step nearest to the centre's peak."""
    t, uz = centre_history(run_dir)
    t_peak = t[int(np.argmax(np.abs(uz)))]
    files = sorted(glob.glob(os.path.join(run_dir, "*.h5")))
    if not files:
        sys.exit(f"plot_roof: no .h5 field file in {run_dir}")
    with h5py.File(files[0], "r") as f:
        xyz = f["/mesh/geometry"][()]
        steps = sorted(f["/steps"].keys(), key=int)
        times = np.array([f[f"/steps/{s}"].attrs["time"] for s in steps])
        k = int(np.argmin(np.abs(times - t_peak)))
        u = f[f"/steps/{steps[k]}/displacement"][()]
    return xyz, xyz + u, times[k]


def peak_w(run_dir):
    """summary.json max_abs_w: the peak |w| over every step and node (the
    drawn state is the stored field step nearest to the centre's peak)."""
    with open(os.path.join(run_dir, "summary.json")) as fh:
        return float(json.load(fh)["max_abs_w"])


def plot_side(out_dir, ax):
    """Cross-sections (y-z) of both runs, each through the node of its peak
    vertical displacement (nodes within 0.3 m of its x) at the stored step
    nearest to the centre's peak, over the undeformed section; true scale."""
    for sub, label, colour in RUNS:
        x0, x1, tk = shape_at_peak(os.path.join(out_dir, sub))
        w = x1[:, 2] - x0[:, 2]
        k = int(np.argmax(np.abs(w)))
        peak = peak_w(os.path.join(out_dir, sub))
        sel = np.abs(x0[:, 0] - x0[k, 0]) < 0.3
        order = np.argsort(x0[sel, 1])
        if sub == RUNS[0][0]:
            ax.plot(x0[sel, 1][order], x0[sel, 2][order], "--", color="0.5", label="undeformed")
        ax.plot(x1[sel, 1][order], x1[sel, 2][order], "-o", color=colour, ms=2.5,
                label=f"{label}: peak |w| {peak:.2f} m; drawn at t = {tk * 1e3:.0f} ms, "
                      f"section x = {x0[k, 0]:.1f} m")
    ax.set_aspect("equal")
    ax.set_xlabel("y (m), across the span")
    ax.set_ylabel("z (m)")
    ax.grid(alpha=0.3)
    ax.set_title("Roof cross-section near its peak vertical displacement (true scale)", fontsize=10)
    # under the axes: the curves fill the panel
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.3), ncol=1, fontsize=8,
              frameon=False)


def plot_histories(out_dir, au, ar):
    for sub, label, colour in RUNS:
        run_dir = os.path.join(out_dir, sub)
        t, uz = centre_history(run_dir)
        au.plot(t * 1e3, uz, color=colour, label=label)
        tr, r = total_reaction(run_dir)
        ar.plot(tr * 1e3, r * 1e-3, color=colour, label=label)
    au.set_ylabel("centre vertical displacement (m)")
    ar.set_ylabel("total support reaction (kN)")
    ar.set_xlabel("t (ms)")
    au.legend(loc="best", fontsize=8)
    ar.legend(loc="best", fontsize=8)
    au.grid(alpha=0.3)
    ar.grid(alpha=0.3)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out_dir")
    ap.add_argument("--image", help="also write a combined picture here")
    args = ap.parse_args()
    for sub, _, _ in RUNS:
        if not os.path.isdir(os.path.join(args.out_dir, sub)):
            sys.exit(f"plot_roof: {args.out_dir}/{sub} is missing (run with compare_without_drag = true)")

    written = []
    fig, ax = plt.subplots(figsize=(8, 3.6), constrained_layout=True)
    plot_side(args.out_dir, ax)
    written.append(os.path.join(args.out_dir, "roof-side.png"))
    fig.savefig(written[-1], dpi=110, bbox_inches="tight")  # equal aspect: crop the margins
    plt.close(fig)

    fig, (au, ar) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, constrained_layout=True)
    plot_histories(args.out_dir, au, ar)
    fig.suptitle("Blast-loaded roof: centre displacement and support reaction")
    written.append(os.path.join(args.out_dir, "roof-history.png"))
    fig.savefig(written[-1], dpi=110)
    plt.close(fig)

    if args.image:
        fig = plt.figure(figsize=(11, 7.5), constrained_layout=True)
        gs = fig.add_gridspec(2, 2, height_ratios=[1, 1.15])
        plot_side(args.out_dir, fig.add_subplot(gs[0, :]))
        au = fig.add_subplot(gs[1, 0])
        ar = fig.add_subplot(gs[1, 1], sharex=au)
        plot_histories(args.out_dir, au, ar)
        au.set_xlabel("t (ms)")
        fig.suptitle("Blast-loaded fabric roof (drag paper, section 5): with and without drag")
        fig.savefig(args.image, dpi=100)
        plt.close(fig)
        written.append(args.image)
    for path in written:
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
