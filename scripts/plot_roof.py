#!/usr/bin/python3
"""Pictures of the blast-loaded roof (drag paper, section 5), with and without drag.

Usage: /usr/bin/python3 scripts/plot_roof.py OUT_DIR [--case CASE] [--image PATH]

OUT_DIR is the output folder of `membrane run cases/membrane/blast-roof.toml`
(compare_without_drag = true): OUT_DIR/with-drag and OUT_DIR/without-drag
each hold <case>.h5 (/mesh/geometry, /steps/<k>/displacement with a `time`
attribute), probes.csv (the probe `centre`) and reactions.csv (columns
<set>_Rx, <set>_Ry, <set>_Rz; the springs, the gables and the beams'
contact forces). CASE (default cases/membrane/blast-roof.toml) gives the
beams: its [[rigid_surface]] arcs. Writes into OUT_DIR:

  roof-side.png     the roof at each run's UPWARD peak (paper Fig. 12): the
                    cross-section across the span through the peak, and the
                    crown line along the roof, with the beams drawn; the
                    crown line at the end of the run too (resting on the beams)
  roof-history.png  centre vertical displacement, and the vertical reaction
                    of the supports (gables and springs) and of the beams
                    (contact) against time (paper Fig. 13)

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
import tomllib

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


def vertical_reactions(run_dir, arcs_names):
    """Time, the vertical force the supports take (sum of the z reactions of
    the gables and the springs) and the one the beams take (their contact
    forces' z components)."""
    header, data = read_csv(os.path.join(run_dir, "reactions.csv"))
    supports, on_beams = np.zeros(data.shape[0]), np.zeros(data.shape[0])
    for j, name in enumerate(header):
        if name.endswith("_Rz"):
            target = on_beams if name[:-3] in arcs_names else supports
            target += data[:, j]
    return data[:, 0], supports, on_beams


def fields(run_dir):
    """(reference nodes, [(time, displacement)] of every stored step)."""
    files = sorted(glob.glob(os.path.join(run_dir, "*.h5")))
    if not files:
        sys.exit(f"plot_roof: no .h5 field file in {run_dir}")
    with h5py.File(files[0], "r") as f:
        xyz = f["/mesh/geometry"][()]
        steps = sorted(f["/steps"].keys(), key=int)
        out = [(float(f[f"/steps/{k}"].attrs["time"]), f[f"/steps/{k}/displacement"][()])
               for k in steps]
    return xyz, out


def upward_peak(run_dir):
    """Time (s) and value (m) of the centre's largest upward displacement."""
    t, uz = centre_history(run_dir)
    k = int(np.argmax(uz))
    return t[k], uz[k]


def beams(case):
    """The case's [[rigid_surface]] arcs as (x of the beam, arc centre z, radius,
    width), and the names of all its rigid surfaces (their reaction columns)."""
    with open(case, "rb") as fh:
        doc = tomllib.load(fh)
    arcs = [r for r in doc.get("rigid_surface", []) if r.get("shape") == "arc"]
    return [(r["center"][0], r["center"][2], r["radius"], r.get("width", 0.0)) for r in arcs], \
        {r.get("name", f"surface{k}") for k, r in enumerate(doc.get("rigid_surface", []))}


def nearest_step(steps, t):
    return min(steps, key=lambda s: abs(s[0] - t))


def plot_section(out_dir, arcs, ax):
    """Cross-section (y-z) of both runs at their upward peak, through the
    node of the largest upward displacement (nodes within 0.3 m of its x),
    over the beam's arc; true scale."""
    y = np.linspace(-5.1, 5.1, 200)
    if arcs:
        _, zc, radius, _ = arcs[0]
        ax.plot(y, zc + np.sqrt(radius ** 2 - y ** 2), color="0.3", lw=3, alpha=0.5,
                label=f"beams (arcs of R = {radius:g} m) and undeformed fabric")
    for sub, label, colour in RUNS:
        run_dir = os.path.join(out_dir, sub)
        x0, steps = fields(run_dir)
        t_peak, w_peak = upward_peak(run_dir)
        tk, u = nearest_step(steps, t_peak)
        k = int(np.argmax(u[:, 2]))
        sel = np.abs(x0[:, 0] - x0[k, 0]) < 0.3
        order = np.argsort(x0[sel, 1])
        x1 = x0 + u
        ax.plot(x1[sel, 1][order], x1[sel, 2][order], "-o", color=colour, ms=2.5,
                label=f"{label}: centre peak {w_peak:.2f} m up at {t_peak * 1e3:.0f} ms; "
                      f"drawn at {tk * 1e3:.0f} ms, section x = {x0[k, 0]:.1f} m")
    ax.set_aspect("equal")
    ax.set_xlabel("y (m), across the span")
    ax.set_ylabel("z (m)")
    ax.grid(alpha=0.3)
    ax.set_title("Across the span at the upward peak (true scale)", fontsize=10)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.25), ncol=1, fontsize=8,
              frameon=False)


def plot_crown(out_dir, arcs, ax):
    """The crown line (nodes within 0.3 m of y = 0) along the roof: at each
    run's upward peak and at the end of the run, with the beams' tops."""
    for xb, zc, radius, width in arcs:
        top = zc + radius
        ax.plot([xb, xb], [top - 0.6, top], color="0.3", lw=3, alpha=0.5)
    if arcs:
        ax.plot([], [], color="0.3", lw=3, alpha=0.5, label="beams (their tops)")
    for sub, label, colour in RUNS:
        run_dir = os.path.join(out_dir, sub)
        x0, steps = fields(run_dir)
        sel = np.abs(x0[:, 1]) < 0.3
        order = np.argsort(x0[sel, 0])
        t_peak, _ = upward_peak(run_dir)
        for (tk, u), style, when in ((nearest_step(steps, t_peak), "-", "upward peak"),
                                     (steps[-1], ":", "end")):
            x1 = x0 + u
            ax.plot(x1[sel, 0][order], x1[sel, 2][order], style, color=colour,
                    label=f"{label}, {when} ({tk * 1e3:.0f} ms)")
    ax.set_xlabel("x (m), along the roof")
    ax.set_ylabel("z (m)")
    ax.grid(alpha=0.3)
    ax.set_title("Along the crown: thrown up, then resting on the beams", fontsize=10)
    ax.legend(loc="best", fontsize=7)


def plot_side(out_dir, arcs, ax_section, ax_crown):
    plot_section(out_dir, arcs, ax_section)
    plot_crown(out_dir, arcs, ax_crown)


def plot_histories(out_dir, au, ar, beam_names):
    for sub, label, colour in RUNS:
        run_dir = os.path.join(out_dir, sub)
        t, uz = centre_history(run_dir)
        au.plot(t * 1e3, uz, color=colour, label=label)
        tr, supports, on_beams = vertical_reactions(run_dir, beam_names)
        ar.plot(tr * 1e3, supports * 1e-3, color=colour, label=f"{label}: supports")
        if beam_names:
            ar.plot(tr * 1e3, on_beams * 1e-3, ":", color=colour, label=f"{label}: beams")
    au.set_ylabel("centre vertical displacement (m)")
    ar.set_ylabel("vertical reaction (kN)")
    ar.set_xlabel("t (ms)")
    au.legend(loc="best", fontsize=8)
    ar.legend(loc="best", fontsize=8)
    au.grid(alpha=0.3)
    ar.grid(alpha=0.3)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out_dir")
    ap.add_argument("--case", default=os.path.join(os.path.dirname(__file__), "..", "cases",
                                                    "membrane", "blast-roof.toml"),
                    help="the case file: its [[rigid_surface]] arcs are the beams drawn")
    ap.add_argument("--image", help="also write a combined picture here")
    args = ap.parse_args()
    for sub, _, _ in RUNS:
        if not os.path.isdir(os.path.join(args.out_dir, sub)):
            sys.exit(f"plot_roof: {args.out_dir}/{sub} is missing (run with compare_without_drag = true)")
    arcs, beam_names = beams(args.case)

    written = []
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 8), constrained_layout=True)
    plot_side(args.out_dir, arcs, a1, a2)
    written.append(os.path.join(args.out_dir, "roof-side.png"))
    fig.savefig(written[-1], dpi=110, bbox_inches="tight")  # equal aspect: crop the margins
    plt.close(fig)

    fig, (au, ar) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, constrained_layout=True)
    plot_histories(args.out_dir, au, ar, beam_names)
    fig.suptitle("Blast-loaded roof: centre displacement and support reaction")
    written.append(os.path.join(args.out_dir, "roof-history.png"))
    fig.savefig(written[-1], dpi=110)
    plt.close(fig)

    if args.image:
        fig = plt.figure(figsize=(12, 10), constrained_layout=True)
        gs = fig.add_gridspec(3, 2, height_ratios=[1.1, 0.9, 1.0])
        plot_side(args.out_dir, arcs, fig.add_subplot(gs[0, :]), fig.add_subplot(gs[1, :]))
        au = fig.add_subplot(gs[2, 0])
        ar = fig.add_subplot(gs[2, 1], sharex=au)
        plot_histories(args.out_dir, au, ar, beam_names)
        au.set_xlabel("t (ms)")
        fig.suptitle("Blast-loaded fabric roof on its beams (drag paper, section 5): "
                     "with and without drag")
        fig.savefig(args.image, dpi=90)
        plt.close(fig)
        written.append(args.image)
    for path in written:
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
