#!/usr/bin/python3
"""Picture of a phase map written by `micro`: two mid-plane slices coloured
by phase and the fraction of inclusion phases (every phase but the first,
the matrix) through the cell along y, with the cell's edges in length units.

Usage: /usr/bin/python3 scripts/plot_cell.py PHASES.h5 [OUT.png] [TITLE]

OUT.png defaults to PHASES.png beside PHASES.h5. Prints "wrote OUT.png".
Reads /phases (N1 x N2 x N3, x slowest) and its attributes size_x, size_y,
size_z (m) and phase_names. docs/images/homogenize-polyurea-cell.png:
  micro cases/cells/polyurea.toml --out /tmp/pu64.h5 --resolution 64
  plot_cell.py /tmp/pu64.h5 docs/images/homogenize-polyurea-cell.png \
      "cases/cells/polyurea.toml at 64^3: hard ellipsoids (19 %) at 45 degrees from z"
"""
import argparse
import os

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import BoundaryNorm, ListedColormap  # noqa: E402

UNITS = ((1e-9, "nm"), (1e-6, "µm"), (1e-3, "mm"), (1.0, "m"))


def length_unit(size):
    """(scale, name): the largest unit in which the edge is at least 1."""
    scale, name = UNITS[0]
    for s, n in UNITS:
        if size >= s:
            scale, name = s, n
    return scale, name


def read_cell(path):
    with h5py.File(path, "r") as f:
        d = f["phases"]
        p = d[...]  # x slowest: p[i, j, k]
        size = [float(d.attrs.get(k, 1.0)) for k in ("size_x", "size_y", "size_z")]
        names = d.attrs.get("phase_names", b"")
    names = names.decode() if isinstance(names, bytes) else str(names)
    names = names.split(",") if names else []
    nphase = int(p.max()) + 1
    names += ["phase %d" % i for i in range(len(names), nphase)]
    return p, size, names


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("phases", metavar="PHASES.h5")
    ap.add_argument("out", metavar="OUT.png", nargs="?")
    ap.add_argument("title", metavar="TITLE", nargs="?")
    a = ap.parse_args()
    out = a.out or os.path.splitext(a.phases)[0] + ".png"
    p, (sx, sy, sz), names = read_cell(a.phases)
    scale, unit = length_unit(max(sx, sy, sz))
    n0, n1, n2 = p.shape
    xz = [0, sx / scale, 0, sz / scale]
    xy = [0, sx / scale, 0, sy / scale]
    views = [(p[:, n1 // 2, :].T, xz, "y = L/2 (x-z plane)", "z"),
             (p[:, :, n2 // 2].T, xy, "z = L/2 (x-y plane)", "y")]

    fig, ax = plt.subplots(1, 3, figsize=(11, 3.6), constrained_layout=True)
    base = plt.get_cmap("viridis")
    cmap = ListedColormap([base(i / max(1, len(names) - 1)) for i in range(len(names))])
    norm = BoundaryNorm(np.arange(len(names) + 1) - 0.5, len(names))
    for a_, (sl, ext, name, yl) in zip(ax[:2], views):
        im = a_.imshow(sl, origin="lower", cmap=cmap, norm=norm, extent=ext,
                       interpolation="nearest")
        a_.set_title(name, fontsize=10)
        a_.set_ylabel("%s (%s)" % (yl, unit))
    bar = fig.colorbar(im, ax=ax[1], ticks=range(len(names)), shrink=0.9)
    bar.ax.set_yticklabels(names)

    frac = (p > 0).mean(axis=1).T
    im = ax[2].imshow(frac, origin="lower", cmap="magma", vmin=0.0, vmax=1.0, extent=xz)
    ax[2].set_title("through the cell along y (x-z plane)", fontsize=10)
    ax[2].set_ylabel("z (%s)" % unit)
    fig.colorbar(im, ax=ax[2], shrink=0.9,
                 label="%s fraction along y" % " + ".join(names[1:] or ["inclusion"]))
    for a_ in ax:
        a_.set_xlabel("x (%s)" % unit)
    fig.suptitle(a.title or a.phases, fontsize=11)
    fig.savefig(out, dpi=100)
    print("wrote " + out)


if __name__ == "__main__":
    main()
