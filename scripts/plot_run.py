#!/usr/bin/python3
"""Pictures of one membrane run: |v| at three moments and the probe histories.

Usage: /usr/bin/python3 scripts/plot_run.py RUN_DIR [--title TEXT]

Reads RUN_DIR/<case>.h5 (written by `membrane run`: /mesh/geometry,
/mesh/topology, /steps/<k>/speed with a `time` attribute) and
RUN_DIR/probes.csv; writes RUN_DIR/speed.png (like Figs. 3-5 of the membrane
paper) and RUN_DIR/probes.png.
"""
import argparse
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
import numpy as np  # noqa: E402


def field_file(run_dir):
    files = sorted(glob.glob(os.path.join(run_dir, "*.h5")))
    if not files:
        sys.exit(f"plot_run: no .h5 field file in {run_dir}")
    return files[0]


def plot_speed(run_dir, title):
    with h5py.File(field_file(run_dir), "r") as f:
        xyz = f["/mesh/geometry"][()]
        tri = f["/mesh/topology"][()]
        steps = sorted(f["/steps"].keys(), key=int)
        if not steps:
            sys.exit(f"plot_run: no time steps in {run_dir}")
        times = np.array([f[f"/steps/{s}"].attrs["time"] for s in steps])
        # three moments: a quarter, half and all of the run (Figs. 3-5 style)
        picks = []
        for frac in (0.25, 0.5, 1.0):
            k = int(np.argmin(np.abs(times - frac * times[-1])))
            if k not in picks:
                picks.append(k)
        speeds = [f[f"/steps/{steps[k]}/speed"][()] for k in picks]
    triang = mtri.Triangulation(xyz[:, 0], xyz[:, 1], tri)
    vmax = max(float(np.max(s)) for s in speeds) or 1.0
    fig, axes = plt.subplots(1, len(picks), figsize=(4.2 * len(picks), 4.4), constrained_layout=True)
    axes = np.atleast_1d(axes)
    for ax, k, s in zip(axes, picks, speeds):
        pc = ax.tripcolor(triang, s, shading="gouraud", cmap="inferno", vmin=0.0, vmax=vmax)
        ax.set_aspect("equal")
        ax.set_title(f"{title}\nt = {times[k] * 1e6:.3g} us" if ax is axes[0] else f"\nt = {times[k] * 1e6:.3g} us", fontsize=10)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
    fig.colorbar(pc, ax=axes.tolist(), label="|v| (m/s)", shrink=0.85)
    out = os.path.join(run_dir, "speed.png")
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


def plot_probes(run_dir, title):
    path = os.path.join(run_dir, "probes.csv")
    if not os.path.exists(path):
        return None
    with open(path) as fh:
        rows = list(csv.reader(fh))
    header, data = rows[0], np.array(rows[1:], dtype=float)
    if data.size == 0:
        return None
    t = data[:, 0] * 1e6
    probes = sorted({h.rsplit("_", 1)[0] for h in header[1:]})
    fig, (au, av) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, constrained_layout=True)
    for p in probes:
        for comp, style in (("z", "-"), ("x", "--")):
            iu, iv = header.index(f"{p}_u{comp}"), header.index(f"{p}_v{comp}")
            au.plot(t, data[:, iu] * 1e3, style, label=f"{p} u{comp}")
            av.plot(t, data[:, iv], style, label=f"{p} v{comp}")
    au.set_ylabel("displacement (mm)")
    av.set_ylabel("velocity (m/s)")
    av.set_xlabel("t (us)")
    au.legend(fontsize=8)
    av.legend(fontsize=8)
    au.grid(alpha=0.3)
    av.grid(alpha=0.3)
    fig.suptitle(title)
    out = os.path.join(run_dir, "probes.png")
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_dir")
    ap.add_argument("--title", default="")
    a = ap.parse_args()
    title = a.title or os.path.basename(os.path.normpath(a.run_dir))
    for out in (plot_speed(a.run_dir, title), plot_probes(a.run_dir, title)):
        if out:
            print(out)


if __name__ == "__main__":
    main()
