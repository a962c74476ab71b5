#!/usr/bin/python3
"""The reduced-order polyurea cell against the full-field nonlinear cell on
the same voxels: stress-strain curves, the agreement table and a plot.

For every path (uniaxial stress, simple shear, confined compression) and rate
it runs the full-field cell (`homogenize CELL --path P --rate R --to S`) and
drives each reduced-order entry (`materials drive NAME --kinematics small`,
the small-strain kinematics of the FFT cell) with the same steps. Runs whose
CSV is already in --work are reused, so an interrupted study continues.

Agreement of a curve: the largest |sigma_rom - sigma_ff| / |sigma_ff| of the
driven stress component over the steps where |sigma_ff| exceeds 5 % of its
peak over the curve.

Usage:
  /usr/bin/python3 scripts/plot_rom.py --cell cases/cells/polyurea-two-scale.toml \
      --partitions 1,8 --rates 1e2,2.6e3,1e5 --to 0.3 --steps 60 \
      --work rom-study --out rom-vs-full-field.png [--schemes tfa,clustering] \
      [--resolution N] [--bin build/bin]
--schemes: the reduced-order schemes (`homogenize --scheme`), each with every
--partitions; one column per pair.
Prints the table (markdown) and writes the plot to --out and the table to
WORK/table.md, printing "wrote PATH" for each."""
import argparse
import csv
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from plot_drive import PATH_WORDS, driven  # noqa: E402

PATHS = ["uniaxial-stress", "shear", "confined"]


def curve(csv_path, path):
    e, s, sign = driven(path)
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    return [sign * float(r[e]) for r in rows], [sign * float(r[s]) for r in rows]


def run(cmd):
    print("+ " + " ".join(cmd), file=sys.stderr, flush=True)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def agreement(ff, rom):
    """Largest relative difference where |ff| exceeds 5 % of its peak."""
    peak = max(abs(v) for v in ff)
    worst = 0.0
    for a, b in zip(ff, rom):
        if abs(a) > 0.05 * peak:
            worst = max(worst, abs(b - a) / abs(a))
    return worst


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--cell", default="cases/cells/polyurea-two-scale.toml")
    ap.add_argument("--partitions", default="1,8", help="partitions per phase, one entry each")
    ap.add_argument("--schemes", default="tfa", help="reduced-order schemes (tfa, clustering)")
    ap.add_argument("--rates", default="1e2,2.6e3,1e5")
    ap.add_argument("--paths", default=",".join(PATHS))
    ap.add_argument("--to", type=float, default=0.3)
    ap.add_argument("--steps", type=int, default=60)
    ap.add_argument("--resolution", type=int, default=0, help="override the cell's (0: keep)")
    ap.add_argument("--bin", default="build/bin")
    ap.add_argument("--work", default="rom-study")
    ap.add_argument("--out", default="rom-vs-full-field.png")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    lib = os.path.join(a.work, "library.toml")
    res = ["--resolution", str(a.resolution)] if a.resolution else []
    rates = a.rates.split(",")
    paths = a.paths.split(",")
    parts = [(sch, int(k)) for sch in a.schemes.split(",") for k in a.partitions.split(",")]

    names = {}
    for sch, k in parts:
        names[(sch, k)] = "rom-%s-k%d" % (sch, k)
        if not os.path.exists(os.path.join(a.work, names[(sch, k)] + ".done")):
            run([os.path.join(a.bin, "homogenize"), a.cell, "--library", lib, "--name",
                 names[(sch, k)], "--reduced-order", "--partitions", str(k), "--scheme", sch,
                 "--overwrite", "--quiet"] + res)
            open(os.path.join(a.work, names[(sch, k)] + ".done"), "w").close()

    table, curves = [], {}
    for path in paths:
        for rate in rates:
            common = ["--path", path, "--rate", rate, "--to", str(a.to), "--steps", str(a.steps)]
            ff = os.path.join(a.work, "ff-%s-%s.csv" % (path, rate))
            if not os.path.exists(ff):
                run([os.path.join(a.bin, "homogenize"), a.cell, "--out", ff + ".part", "--quiet"]
                    + common + res)
                os.replace(ff + ".part", ff)
            curves[(path, rate, "ff")] = curve(ff, path)
            row = [path, rate]
            for sch, k in parts:
                rom = os.path.join(a.work, "%s-%s-%s.csv" % (names[(sch, k)], path, rate))
                run([os.path.join(a.bin, "materials"), "drive", names[(sch, k)], "--library", lib,
                     "--kinematics", "small", "--out", rom] + common)
                curves[(path, rate, sch, k)] = curve(rom, path)
                row.append(agreement(curves[(path, rate, "ff")][1],
                                     curves[(path, rate, sch, k)][1]))
            table.append(row)

    head = "| path | rate (1/s) | " + " | ".join("%s, %d per phase" % p for p in parts) + " |"
    lines = [head, "|" + "---|" * (2 + len(parts))]
    for row in table:
        lines.append("| %s | %s | " % (row[0], row[1]) +
                     " | ".join("%.2f %%" % (100 * v) for v in row[2:]) + " |")
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.path.join(a.work, "table.md"), "w") as f:
        f.write(text)

    fig, axes = plt.subplots(1, len(paths), figsize=(4.6 * len(paths), 4.4),
                             constrained_layout=True)
    if len(paths) == 1:
        axes = [axes]
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    styles = ["--", ":", "-.", (0, (3, 1, 1, 1, 1, 1)), (0, (1, 3))]
    for ax, path in zip(axes, paths):
        for c, rate in enumerate(rates):
            e, s = curves[(path, rate, "ff")]
            ax.plot(e, [v / 1e6 for v in s], "-", color=colours[c], label="%s /s" % rate)
            for j, (sch, k) in enumerate(parts):
                e, s = curves[(path, rate, sch, k)]
                ax.plot(e, [v / 1e6 for v in s], linestyle=styles[j % len(styles)],
                        color=colours[c])
        ax.set_title(PATH_WORDS[path], fontsize=10)
        e, s, _ = driven(path)
        sign = "-" if path == "confined" else ""
        ax.set_xlabel("strain %s%s" % (sign, e.replace("eps_xy", "gamma_xy")))
        ax.set_ylabel("stress %s%s (MPa)" % (sign, s))
        ax.grid(alpha=0.3)
    # one legend for all panels, under them: colour = rate, line style = model
    handles = [plt.Line2D([], [], color=colours[c], label="%s /s" % r) for c, r in enumerate(rates)]
    handles.append(plt.Line2D([], [], color="k", ls="-", label="full field"))
    handles += [plt.Line2D([], [], color="k", ls=styles[j % len(styles)],
                           label="%s, %d per phase" % p) for j, p in enumerate(parts)]
    fig.legend(handles=handles, loc="lower center", bbox_to_anchor=(0.5, 0.0),
               ncol=len(handles), fontsize=8, frameon=False)
    fig.get_layout_engine().set(rect=(0, 0.07, 1, 0.93))
    fig.suptitle("Reduced-order against full-field cell (%s): driven stress at %d rates"
                 % (os.path.basename(a.cell), len(rates)))
    fig.savefig(a.out, dpi=110)
    print("wrote " + a.out)
    print("wrote " + os.path.join(a.work, "table.md"))


if __name__ == "__main__":
    main()
