#!/usr/bin/python3
"""Stress-strain curves of `materials drive` (several rates on one plot), or of
any CSV with its header (`homogenize ... --out`), on one picture.

Usage:
  /usr/bin/python3 scripts/plot_drive.py NAME --path shear --to 0.5 \
      --rates 1e-3,1,1e3,1e5,1e6 [--out PNG] [--materials BIN] [--library P]
      [--steps N] [--unload]
  /usr/bin/python3 scripts/plot_drive.py --csv A.csv:LABEL --csv B.csv:LABEL \
      --path shear [--out PNG] [--title TEXT]

--out defaults to NAME-PATH.png (curves-PATH.png with --csv only) in the
current folder; prints "wrote PNG".

The driven pair is plotted: shear -> (eps_xy, sig_xy); uniaxial-strain and
uniaxial-stress and biaxial-stress -> (eps_xx, sig_xx); confined -> (-eps_xx, -sig_xx), i.e.
compression positive. Stress in MPa."""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def columns(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows


# the paths of `materials drive` in words (titles; also plot_rom.py)
PATH_WORDS = {"shear": "simple shear", "confined": "confined compression",
              "uniaxial-stress": "uniaxial stress", "uniaxial-strain": "uniaxial strain",
              "biaxial-stress": "equibiaxial plane stress"}


def driven(path):
    """(strain column, stress column, sign) of the driven pair; compression positive
    (also plot_rom.py)."""
    if path == "shear":
        return "eps_xy", "sig_xy", 1.0
    if path == "confined":
        return "eps_xx", "sig_xx", -1.0
    return "eps_xx", "sig_xx", 1.0


def pair(rows, path):
    e, s, sign = driven(path)
    return ([sign * float(r[e]) for r in rows], [sign * float(r[s]) / 1e6 for r in rows])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("name", nargs="?")
    ap.add_argument("--path", default="shear",
                    choices=["uniaxial-stress", "uniaxial-strain", "shear", "confined",
                             "biaxial-stress"])
    ap.add_argument("--to", type=float, default=0.5)
    ap.add_argument("--rates", default="1e-3,1,1e3,1e5,1e6")
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--unload", action="store_true")
    ap.add_argument("--materials", default=None, help="materials program (default: build/bin)")
    ap.add_argument("--library", default=None)
    ap.add_argument("--csv", action="append", default=[], help="FILE.csv:LABEL (repeat)")
    ap.add_argument("--title", default=None)
    ap.add_argument("--out", help="PNG to write (default: NAME-PATH.png, or curves-PATH.png)")
    a = ap.parse_args()

    curves = []
    for item in a.csv:
        f, _, label = item.partition(":")
        curves.append((label or os.path.basename(f), columns(f)))
    if a.name:
        prog = a.materials or os.path.join(os.path.dirname(__file__), "..", "build", "bin", "materials")
        with tempfile.TemporaryDirectory() as tmp:
            for rate in a.rates.split(","):
                out = os.path.join(tmp, "r%s.csv" % rate)
                cmd = [prog, "drive", a.name, "--path", a.path, "--rate", rate, "--to", str(a.to),
                       "--steps", str(a.steps), "--out", out]
                if a.unload:
                    cmd.append("--unload")
                if a.library:
                    cmd += ["--library", a.library]
                # its "drove ... in FILE" line names a temporary file: shown only on failure
                done = subprocess.run(cmd, capture_output=True, text=True)
                if done.returncode != 0:
                    sys.exit("plot_drive: %s failed:\n%s%s" % (" ".join(cmd), done.stdout,
                                                                 done.stderr))
                curves.append(("%s /s" % rate, columns(out)))
    if not curves:
        sys.exit("nothing to plot: give NAME or --csv")
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for label, rows in curves:
        x, y = pair(rows, a.path)
        ax.plot(x, y, label=label)
    names = {"shear": ("shear strain gamma_xy", "shear stress sigma_xy (MPa)"),
             "confined": ("compressive strain -eps_xx", "compressive stress -sigma_xx (MPa)")}
    xl, yl = names.get(a.path, ("strain eps_xx", "stress sigma_xx (MPa)"))
    ax.set_xlabel(xl)
    ax.set_ylabel(yl)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, title="strain rate" if a.name and not a.csv else None,
              title_fontsize=8)
    words = PATH_WORDS[a.path]
    if a.unload:
        words += ", load and unload"
    ax.set_title(a.title or (", ".join(filter(None, [a.name, words]))), fontsize=10)
    fig.tight_layout()
    out = a.out or "%s-%s.png" % (a.name or "curves", a.path)
    fig.savefig(out, dpi=90)
    print("wrote " + out)


if __name__ == "__main__":
    main()
