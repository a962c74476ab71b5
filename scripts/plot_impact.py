#!/usr/bin/python3
"""Projectile velocity against time for sheet-impact runs, one curve per run,
and the energy dissipated in the sheet per run.

Usage: /usr/bin/python3 scripts/plot_impact.py OUT_DIR... [--label TEXT]... [--out PNG]
                                               [--probe NAME] [--title TEXT]

Each OUT_DIR is the output folder of `membrane run` on a projectile case
(cases/membrane/polyurea-sheet-impact.toml): its probes.csv holds the probe
PROBE (default "centre", at the projectile: its velocity is the
projectile's) and its summary.json the energies. --label names the runs in
order (default: the folder names). Writes PNG (default
OUT_DIR_1/../impact-velocity.png), prints "wrote PATH", then a table per run:
the impact velocity and the velocity at the end (m/s, along z), the time the
projectile first stops (us; "-" if it never does), the sheet's inelastic
dissipation (summary.json energy.inelastic_dissipation, the work the law does
not store; 0 for an elastic law) and the strain and kinetic energies at the
end (J).
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def fail(message):
    sys.exit(f"plot_impact: {message}")


def probe_velocity(run_dir, probe):
    """Time (s) and the probe's velocity along z (m/s) from run_dir/probes.csv."""
    path = os.path.join(run_dir, "probes.csv")
    if not os.path.isfile(path):
        fail(f"{path} does not exist (is {run_dir} the output folder of `membrane run`?)")
    with open(path) as fh:
        rows = list(csv.reader(fh))
    if len(rows) < 2:
        fail(f"{path} has no data rows")
    column = f"{probe}_vz"
    if column not in rows[0]:
        fail(f"{path} has no column {column} (columns: {', '.join(rows[0])})")
    data = np.array(rows[1:], dtype=float)
    return data[:, 0], data[:, rows[0].index(column)]


def summary(run_dir):
    path = os.path.join(run_dir, "summary.json")
    if not os.path.isfile(path):
        fail(f"{path} does not exist (the run did not finish?)")
    with open(path) as fh:
        return json.load(fh)


def energy(s, key):
    """summary.json energy.KEY, 0 when the run does not report it (elastic laws)."""
    return float(s.get("energy", {}).get(key, 0.0))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+", metavar="OUT_DIR")
    ap.add_argument("--label", action="append", default=[], help="one per run, in order")
    ap.add_argument("--out", help="PNG to write")
    ap.add_argument("--probe", default="centre")
    ap.add_argument("--title", default="Projectile velocity, polyurea sheet impact")
    args = ap.parse_args()
    if args.label and len(args.label) != len(args.runs):
        fail(f"{len(args.label)} --label for {len(args.runs)} runs: give one per run or none")
    labels = args.label or [os.path.basename(os.path.normpath(r)) for r in args.runs]
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.runs[0])),
                                   "impact-velocity.png")

    fig, ax = plt.subplots(figsize=(7.5, 4.6))
    rows = []
    for run_dir, label in zip(args.runs, labels):
        t, vz = probe_velocity(run_dir, args.probe)
        s = summary(run_dir)
        ax.plot(1e6 * t, vz, label=label, lw=1.6)
        stopped = np.nonzero(vz * vz[0] <= 0.0)[0]
        t_stop = 1e6 * t[stopped[0]] if stopped.size else None
        rows.append((label, vz[0], vz[-1], t_stop, energy(s, "inelastic_dissipation"),
                     energy(s, "strain"), energy(s, "kinetic")))
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel("time (us)")
    ax.set_ylabel("projectile velocity v_z (m/s)")
    ax.set_title(args.title)
    ax.grid(alpha=0.3)
    # The legend under the axes: never over the curves.
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=min(3, len(rows)),
              frameon=False)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")

    print()
    print(f"{'law':<28} {'v0 (m/s)':>9} {'v_end (m/s)':>11} {'stops at (us)':>13} "
          f"{'dissipated (J)':>14} {'strain (J)':>10} {'kinetic (J)':>11}")
    for label, v0, v1, t_stop, diss, strain, kin in rows:
        stop = f"{t_stop:13.1f}" if t_stop is not None else f"{'-':>13}"
        print(f"{label:<28} {v0:9.2f} {v1:11.2f} {stop} {diss:14.4g} {strain:10.4g} {kin:11.4g}")
    print("(dissipated: summary.json energy.inelastic_dissipation, the work the law does not "
          "store; strain, kinetic: at the end, sheet and projectile)")


if __name__ == "__main__":
    main()
