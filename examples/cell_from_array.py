#!/usr/bin/python3
"""A cell from a numpy label array: a random section of E-glass fibres along
z in soft polyurea (discs in x-y, extruded along z), homogenized; prints the
transverse and axial moduli.

    PYTHONPATH=build/python /usr/bin/python3 examples/cell_from_array.py --out out/fibres

The array's axis 0 is x, axis 1 y, axis 2 z. It is int32, C-ordered and its
ids are 0..P-1, so the cell uses it without a copy. The cell is invariant
along z, so a few voxels suffice there (as in cases/cells/fiber.toml).
"""
import argparse
import pathlib

import matplotlib
import numpy as np

import lamina

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend)


def random_section(n, count, radius, rng):
    """An n x n section (axis 0 = x) of `count` non-overlapping discs of
    `radius` voxels placed at random, periodic: 1 in a disc, 0 elsewhere."""
    centres = []
    for _ in range(100000):
        if len(centres) == count:
            break
        c = rng.uniform(0, n, 2)
        d = [np.abs((c - o + n / 2) % n - n / 2) for o in centres]  # periodic distance
        if all(np.hypot(*x) > 2.2 * radius for x in d):
            centres.append(c)
    else:
        raise SystemExit(f"no room for {count} discs of radius {radius} in {n} x {n}")
    x = np.arange(n) + 0.5
    X, Y = np.meshgrid(x, x, indexing="ij")
    section = np.zeros((n, n), dtype=np.int32)
    for cx, cy in centres:
        dx = (X - cx + n / 2) % n - n / 2
        dy = (Y - cy + n / 2) % n - n / 2
        section[dx ** 2 + dy ** 2 <= radius ** 2] = 1
    return section


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=".", help="folder of fibre_section.png")
    parser.add_argument("--small", action="store_true", help="tiny sizes (CI)")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    n, nz, count = (16, 2, 3) if args.small else (96, 4, 12)
    radius = (0.15 if args.small else 0.09) * n  # voxels: 21 % (small), 30 % of fibres
    edge = 100e-6  # m, the section's edge

    section = random_section(n, count, radius, np.random.default_rng(args.seed))
    labels = np.repeat(section[:, :, np.newaxis], nz, axis=2)  # C order, int32
    phases = {0: {"name": "matrix", "catalog": "polyurea-soft"},
              1: {"name": "fiber", "catalog": "e-glass"}}
    cell = lamina.Cell.from_array(labels, phases, size=(edge, edge, edge * nz / n))
    print(f"cell {cell.resolution}, fibre fraction {cell.phase_fractions['fiber']:.3f}, "
          f"label array copied: {cell.copied}")

    result = lamina.homogenize(cell)
    S = np.linalg.inv(result.C)  # compliance; lamina order xx, yy, zz, xy, yz, xz
    moduli = {"E_x (transverse)": 1 / S[0, 0], "E_y (transverse)": 1 / S[1, 1],
              "E_z (axial)": 1 / S[2, 2], "G_xy (transverse)": 1 / S[3, 3],
              "G_yz (axial)": 1 / S[4, 4], "G_xz (axial)": 1 / S[5, 5]}
    for name, value in moduli.items():
        print(f"{name:18s} {value / 1e9:8.3f} GPa")
    print(f"density {result.density:.1f} kg/m^3, CG iterations {result.iterations}")

    fig, ax = plt.subplots(figsize=(4.5, 4))
    ax.imshow(section.T, origin="lower", extent=(0, edge * 1e6, 0, edge * 1e6), cmap="Greys")
    ax.set(xlabel="x (um)", ylabel="y (um)",
           title=f"E_z = {moduli['E_z (axial)'] / 1e9:.2f} GPa, "
                 f"E_x = {moduli['E_x (transverse)'] / 1e9:.2f} GPa")
    fig.tight_layout()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "fibre_section.png", dpi=120)
    print("wrote", out / "fibre_section.png")


if __name__ == "__main__":
    main()
