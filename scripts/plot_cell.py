#!/usr/bin/python3
"""Picture of a phase map written by `micro`: two mid-plane slices and the
fraction of inclusion phase averaged along y.
Usage: /usr/bin/python3 scripts/plot_cell.py PHASES.h5 OUT.png [TITLE]
(docs/images/homogenize-polyurea-cell.png: micro cases/cells/polyurea.toml
--out /tmp/pu64.h5 --resolution 64, then this script.)"""
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

p = h5py.File(sys.argv[1], "r")["phases"][...]  # x slowest: p[i, j, k]
title = sys.argv[3] if len(sys.argv) > 3 else sys.argv[1]
fig, ax = plt.subplots(1, 3, figsize=(10, 3.4))
n0, n1, n2 = p.shape
views = [(p[:, n1 // 2, :].T, "y = L/2 (x-z plane)", "x", "z"),
         (p[:, :, n2 // 2].T, "z = L/2 (x-y plane)", "x", "y"),
         ((p > 0).mean(axis=1).T, "inclusion fraction along y", "x", "z")]
for a, (sl, name, xl, yl) in zip(ax, views):
    a.imshow(sl, origin="lower", cmap="viridis", extent=[0, 1, 0, 1])
    a.set_title(name, fontsize=9)
    a.set_xlabel(xl)
    a.set_ylabel(yl)
fig.suptitle(title, fontsize=10)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=90)
