#!/usr/bin/python3
"""Volume-fraction sweep of the sphere cell (cases/cells/sphere.toml): the
effective bulk and shear moduli of the homogenized cell against the
Hashin-Shtrikman bounds of its two phases.

    PYTHONPATH=build/python /usr/bin/python3 examples/sweep_sphere_fraction.py --out out/sweep

The cell has cubic symmetry: its bulk modulus (C11 + 2 C12) / 3 lies between
the bounds. It has two shear moduli, C44 (lamina order: C[3, 3], xy) and
(C11 - C12) / 2, which need not (the shear bounds are for isotropic
composites; C44 of this simple cubic array falls below the lower one), while
their isotropic (Voigt) average (C11 - C12 + 3 C44) / 5 lies between. The x
axis is the sphere's voxel fraction, which is what the bounds are for.
"""
import argparse
import pathlib
import tomllib

import matplotlib
import numpy as np

import lamina

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend)

ROOT = pathlib.Path(__file__).resolve().parents[1]


def bulk_shear(phase):
    """K and mu of an isotropic phase table (E, nu)."""
    E, nu = phase["E"], phase["nu"]
    return E / (3 * (1 - 2 * nu)), E / (2 * (1 + nu))


def hashin_shtrikman(K1, mu1, K2, mu2, f2):
    """The HS bounds (lower, upper) on K and on mu of phases 1 (fraction
    1 - f2) and 2 (fraction f2), for K2 >= K1 and mu2 >= mu1."""
    f1 = 1 - f2
    K_lo = K1 + f2 / (1 / (K2 - K1) + 3 * f1 / (3 * K1 + 4 * mu1))
    K_up = K2 + f1 / (1 / (K1 - K2) + 3 * f2 / (3 * K2 + 4 * mu2))
    mu_lo = mu1 + f2 / (1 / (mu2 - mu1) + 6 * f1 * (K1 + 2 * mu1) / (5 * mu1 * (3 * K1 + 4 * mu1)))
    mu_up = mu2 + f1 / (1 / (mu1 - mu2) + 6 * f2 * (K2 + 2 * mu2) / (5 * mu2 * (3 * K2 + 4 * mu2)))
    return (K_lo, K_up), (mu_lo, mu_up)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cell", default=ROOT / "cases" / "cells" / "sphere.toml")
    parser.add_argument("--out", default=".", help="folder of sphere_sweep.png")
    parser.add_argument("--small", action="store_true", help="tiny sizes (CI)")
    args = parser.parse_args()
    fractions = [0.1, 0.3] if args.small else np.arange(0.05, 0.50, 0.05)
    resolution = 12 if args.small else 32

    with open(args.cell, "rb") as f:
        phases = {p["name"]: p for p in tomllib.load(f)["phases"]}
    K1, mu1 = bulk_shear(phases["matrix"])
    K2, mu2 = bulk_shear(phases["sphere"])

    rows = []
    for f in fractions:
        cell = lamina.Cell.from_file(args.cell, set={"inclusions[0].volume_fraction": float(f),
                                                     "cell.resolution": resolution})
        C = lamina.homogenize(cell).C
        fraction = cell.phase_fractions["sphere"]
        c44, cp = C[3, 3], (C[0, 0] - C[0, 1]) / 2
        rows.append((fraction, C[:3, :3].sum() / 9, c44, cp, (2 * cp + 3 * c44) / 5))
        print(f"f = {fraction:.3f}: K = {rows[-1][1] / 1e9:.3f} GPa, C44 = {c44 / 1e6:.1f} MPa, "
              f"(C11 - C12)/2 = {cp / 1e6:.1f} MPa, average {rows[-1][4] / 1e6:.1f} MPa")
    f, K, c44, cp, mu = np.array(rows).T
    (K_lo, K_up), (mu_lo, mu_up) = hashin_shtrikman(K1, mu1, K2, mu2, f)
    inside = [bool(np.all((lo <= x) & (x <= up))) for x, lo, up in ((K, K_lo, K_up),
                                                                    (mu, mu_lo, mu_up))]
    print("inside the HS bounds (K, average shear):", inside)

    grid = np.linspace(0, max(f.max(), 0.5), 101)
    (K_lo, K_up), (mu_lo, mu_up) = hashin_shtrikman(K1, mu1, K2, mu2, grid)
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    left.fill_between(grid, K_lo / 1e9, K_up / 1e9, alpha=0.3, label="HS bounds")
    left.plot(f, K / 1e9, "o", label="FFT, (C11 + 2 C12) / 3")
    left.set(xlabel="sphere voxel fraction", ylabel="bulk modulus (GPa)")
    right.fill_between(grid, mu_lo / 1e6, mu_up / 1e6, alpha=0.3, label="HS bounds")
    right.plot(f, c44 / 1e6, "o", label="FFT, C44")
    right.plot(f, cp / 1e6, "s", label="FFT, (C11 - C12) / 2")
    right.plot(f, mu / 1e6, "k^", label="FFT, (C11 - C12 + 3 C44) / 5")
    right.set(xlabel="sphere voxel fraction", ylabel="shear modulus (MPa)")
    for ax in (left, right):
        ax.legend()
    fig.suptitle(f"{pathlib.Path(args.cell).name} at {resolution}^3")
    fig.tight_layout()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "sphere_sweep.png", dpi=120)
    print("wrote", out / "sphere_sweep.png")


if __name__ == "__main__":
    main()
