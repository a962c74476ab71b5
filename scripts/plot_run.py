#!/usr/bin/python3
"""Pictures of one membrane run: |v| at three moments and the probe histories.

Usage: /usr/bin/python3 scripts/plot_run.py RUN_DIR [--title TEXT]

Reads RUN_DIR/<case>.h5 (written by `membrane run`: /mesh/geometry,
/mesh/topology, /steps/<k>/speed with a `time` attribute) and
RUN_DIR/probes.csv; writes RUN_DIR/speed.png (like Figs. 3-5 of the membrane
paper) and RUN_DIR/probes.png (when the run has probes), and prints "wrote
PATH" for each.
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
    # panels of the membrane's own aspect, about 3 in wide, room for the titles
    span = np.ptp(xyz[:, :2], axis=0)
    aspect = float(span[1] / span[0]) if span[0] > 0 else 1.0
    fig, axes = plt.subplots(1, len(picks), constrained_layout=True,
                             figsize=(3.6 * len(picks) + 1.4, 3.0 * min(aspect, 2.0) + 1.2))
    axes = np.atleast_1d(axes)
    for ax, k, s in zip(axes, picks, speeds):
        pc = ax.tripcolor(triang, s, shading="gouraud", cmap="inferno", vmin=0.0, vmax=vmax)
        ax.set_aspect("equal")
        ax.set_title(f"t = {times[k] * 1e6:.3g} us", fontsize=10)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
    fig.colorbar(pc, ax=axes.tolist(), label="speed |v| (m/s)", shrink=0.9, pad=0.02)
    fig.suptitle(f"{title}: speed |v| of the membrane")
    out = os.path.join(run_dir, "speed.png")
    fig.savefig(out, dpi=110, bbox_inches="tight")  # equal aspect: crop the margins
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
    fig, (au, av) = plt.subplots(2, 1, figsize=(8.5, 6), sharex=True, constrained_layout=True)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for j, p in enumerate(probes):
        for comp, style, name in (("z", "-", "z, out of plane"), ("x", "--", "x, in plane")):
            iu, iv = header.index(f"{p}_u{comp}"), header.index(f"{p}_v{comp}")
            colour = colours[j % len(colours)]
            au.plot(t, data[:, iu] * 1e3, style, color=colour, label=f"{p}: {name}")
            av.plot(t, data[:, iv], style, color=colour)
    au.set_ylabel("displacement (mm)")
    av.set_ylabel("velocity (m/s)")
    av.set_xlabel("t (us)")
    # one legend for both panels, beside them: never over the curves
    au.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, title="probe: component")
    au.grid(alpha=0.3)
    av.grid(alpha=0.3)
    fig.suptitle(f"{title}: probe displacements and velocities")
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
            print(f"wrote {out}")


if __name__ == "__main__":
    main()
