#!/usr/bin/python3
"""The dispersed pulse of cases/membrane/laminate-pulse.toml: the membrane
run with micro-inertia, the one without, and two semi-analytic references.

Usage: /usr/bin/python3 scripts/plot_dispersion.py RUN_ON RUN_OFF \
           --cell cases/cells/laminate.toml [--out laminate-pulse.png]

Writes --out (default laminate-pulse.png in the current folder) and prints
"wrote PATH".

Reads RUN_*/probes.csv (t, <probe>_vx ... of `membrane run`) and the cell
file with its two phases from materials/catalog.toml (isotropic or GVBO at
J = 1: E, nu, density), layers normal to x. References for the signalling
problem v(0, t) = V(t) of a right-going wave, v(x, w) = V(w) exp(-i k(w) x):
  - exact laminate: k(w) from Rytov's Floquet-Bloch relation of the bilayer
    (S. M. Rytov, Sov. Phys. Acoust. 2 (1956) 68),
    cos kL = cos(w a) cos(w b) - (Z1/Z2 + Z2/Z1)/2 sin(w a) sin(w b);
  - the micro-inertia model: w^2 (rho + zeta^2 D k^2) = C k^2 with
    zeta^2 D = phi1^2 phi2^2 M_h^2 (M1 r1 - M2 r2)^2 L^2 / (12 M1^2 M2^2 rho),
    the bilayer's D_lin (docs/homogenize-solver.md), C = M_h.
Prints the relative L2 distance of each run to the exact laminate at each
probe. Plane strain P waves: M = lambda + 2 mu of each layer.
"""
import argparse
import csv
import os
import sys
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def read_probes(run_dir):
    path = os.path.join(run_dir, "probes.csv")
    if not os.path.exists(path):
        sys.exit(f"plot_dispersion: no probes.csv in {run_dir}")
    with open(path) as f:
        rows = list(csv.reader(f))
    head = rows[0]
    data = np.array([[float(x) for x in r] for r in rows[1:]])
    return {h: data[:, i] for i, h in enumerate(head)}


def phase_of(entry, catalog):
    """E, nu, density of a cell phase (inline or from the catalog)."""
    src = catalog[entry["catalog"]] if "catalog" in entry else entry
    return src["E"], src["nu"], entry.get("density", src["density"])


def bilayer(cell_path):
    with open(cell_path, "rb") as f:
        cell = tomllib.load(f)
    with open(os.path.join(HERE, "..", "materials", "catalog.toml"), "rb") as f:
        catalog = tomllib.load(f)
    size = cell["cell"]["size"]
    L = size[0] if isinstance(size, list) else size
    inc = cell["inclusions"][0]
    d2 = inc["thickness"]  # the layer phase (second), the rest is the matrix
    layers = []
    for ph in cell["phases"]:
        E, nu, rho = phase_of(ph, catalog)
        M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))  # lambda + 2 mu
        layers.append((M, rho))
    (M1, r1), (M2, r2) = layers
    return L, L - d2, d2, M1, r1, M2, r2


def wavenumbers(w, L, d1, d2, M1, r1, M2, r2):
    """k(w) of the exact laminate and of the micro-inertia model (nan: no
    propagating wave)."""
    c1, c2 = np.sqrt(M1 / r1), np.sqrt(M2 / r2)
    z = np.sqrt(M1 * r1) / np.sqrt(M2 * r2)
    chi = 0.5 * (z + 1 / z)
    F = np.cos(w * d1 / c1) * np.cos(w * d2 / c2) - chi * np.sin(w * d1 / c1) * np.sin(w * d2 / c2)
    k_exact = np.where(np.abs(F) <= 1, np.arccos(np.clip(F, -1, 1)) / L, np.nan)
    f1, f2 = d1 / L, d2 / L
    Mh = 1 / (f1 / M1 + f2 / M2)
    rho = f1 * r1 + f2 * r2
    disp = f1**2 * f2**2 * Mh**2 * (M1 * r1 - M2 * r2) ** 2 * L**2 / (12 * M1**2 * M2**2 * rho)
    denom = Mh - disp * w**2
    k_model = np.where(denom > 0, w * np.sqrt(rho / np.abs(denom)), np.nan)
    return k_exact, k_model, Mh, rho, disp


def signal(t, V, x, k):
    """v(x, t) of a right-going wave driven by v(0, t) = V(t) (zero padded)."""
    n = 8 * len(t)
    dt = t[1] - t[0]
    Vh = np.fft.rfft(V, n)
    w = 2 * np.pi * np.fft.rfftfreq(n, dt)
    kk = k(w)
    prop = np.where(np.isnan(kk), 0.0, np.exp(-1j * np.nan_to_num(kk) * x))
    return np.fft.irfft(Vh * prop, n)[: len(t)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run_on")
    ap.add_argument("run_off")
    ap.add_argument("--cell", required=True)
    ap.add_argument("--out", default="laminate-pulse.png", help="PNG to write")
    args = ap.parse_args()
    on, off = read_probes(args.run_on), read_probes(args.run_off)
    L, d1, d2, M1, r1, M2, r2 = bilayer(args.cell)
    t = on["t"]
    # the imposed velocity of the strike: read back from the case's Hann pulse
    T = 20e-6
    V = np.where(t < T, np.sin(np.pi * np.minimum(t, T) / T) ** 2, 0.0)
    _, _, Mh, rho, disp = wavenumbers(np.array([1.0]), L, d1, d2, M1, r1, M2, r2)
    print(f"laminate: M_h = {Mh:.6g} Pa, rho = {rho:.6g} kg/m^3, zeta^2 D_xx = {disp:.6g} kg/m, "
          f"l = {np.sqrt(disp / rho):.4g} m, c = {np.sqrt(Mh / rho):.6g} m/s")
    probes = [h[:-3] for h in on if h.endswith("_vx")]
    fig, axes = plt.subplots(len(probes), 1, figsize=(8, 2.4 * len(probes)))
    for ax, p in zip(np.atleast_1d(axes), probes):
        x = float(p[1:]) * 1e-3  # probes are named x<mm>
        exact = signal(t, V, x, lambda w: wavenumbers(w, L, d1, d2, M1, r1, M2, r2)[0])
        model = signal(t, V, x, lambda w: wavenumbers(w, L, d1, d2, M1, r1, M2, r2)[1])
        norm = np.linalg.norm(exact)
        e_on = np.linalg.norm(on[p + "_vx"] - exact) / norm
        e_off = np.linalg.norm(off[p + "_vx"] - exact) / norm
        e_model = np.linalg.norm(model - exact) / norm
        print(f"x = {x:.3f} m: L2 distance to the exact laminate: membrane with micro-inertia "
              f"{e_on:.3f}, without {e_off:.3f}; continuum micro-inertia model {e_model:.3f}; "
              f"peak v exact {exact.max():.4f}, on {on[p + '_vx'].max():.4f}, "
              f"off {off[p + '_vx'].max():.4f} m/s")
        ms = t * 1e6
        ax.plot(ms, off[p + "_vx"], color="0.6", lw=1.2, label="homogenized, no micro-inertia")
        ax.plot(ms, on[p + "_vx"], color="C3", lw=1.4, label="with micro-inertia (zeta^2 D)")
        ax.plot(ms, exact, "k--", lw=1.0, label="exact laminate (Rytov Floquet-Bloch)")
        ax.set_ylabel(f"v_x at x = {x * 1e3:.0f} mm (m/s)")
        ax.grid(alpha=0.3)
        arrival = x / np.sqrt(Mh / rho) * 1e6
        ax.set_xlim(arrival - 15, arrival + 45)
    np.atleast_1d(axes)[0].legend(loc="upper right", fontsize=8)
    np.atleast_1d(axes)[-1].set_xlabel("t (us)")
    fig.suptitle("20 us pulse through a steel / polyurea laminate (period 2 mm): membrane runs")
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
