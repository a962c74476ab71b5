"""Cells from arrays and files against numbers from outside the code: a
laminate of whole voxel layers normal to x equals the exact laminate
stiffness (the continuity conditions of a layered medium: in-plane strains
and the tractions on the layer planes are uniform, so the partial inverse
mixing them is averaged arithmetically), and the 19 % sphere cell's bulk
and shear moduli lie within the Hashin-Shtrikman bounds of its phases at
its voxel fractions."""

import lamina
import numpy as np
import pytest

# lamina order xx yy zz xy yz xz (engineering shear): with the layer normal
# along x the tractions are xx, xy, xz and the in-plane strains yy, zz, yz
T, P = [0, 3, 5], [1, 2, 4]


def isotropic(E, nu):
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    C = np.zeros((6, 6))
    C[:3, :3] = lam
    C[[0, 1, 2], [0, 1, 2]] += 2 * mu
    C[[3, 4, 5], [3, 4, 5]] = mu
    return C


def exact_laminate(stiffnesses, fractions):
    """[sigma_P; eps_T] = H [eps_P; sigma_T] in each layer; eps_P and sigma_T
    are the same in every layer, so the laminate's H is the average."""
    H = np.zeros((6, 6))
    for C, f in zip(stiffnesses, fractions):
        inv = np.linalg.inv(C[np.ix_(T, T)])
        H[:3, :3] += f * (C[np.ix_(P, P)] - C[np.ix_(P, T)] @ inv @ C[np.ix_(T, P)])
        H[:3, 3:] += f * (C[np.ix_(P, T)] @ inv)
        H[3:, :3] += f * (-inv @ C[np.ix_(T, P)])
        H[3:, 3:] += f * inv
    A = np.linalg.inv(H[3:, 3:])  # back from the partial inverse
    C = np.zeros((6, 6))
    C[np.ix_(T, T)] = A
    C[np.ix_(T, P)] = -A @ H[3:, :3]
    C[np.ix_(P, T)] = H[:3, 3:] @ A
    C[np.ix_(P, P)] = H[:3, :3] - H[:3, 3:] @ A @ H[3:, :3]
    return C


def test_layers_along_x_give_the_exact_laminate():
    labels = np.zeros((10, 2, 2), dtype=np.int8)  # 4 of 10 layers stiff: 40 %
    labels[3:7] = 1
    phases = {0: dict(name="soft", law="isotropic", E=1e9, nu=0.3, density=1000.0),
              1: dict(name="stiff", law="isotropic", E=20e9, nu=0.2, density=3000.0)}
    cell = lamina.Cell.from_array(labels, phases, size=1e-3)
    assert cell.phase_fractions == {"soft": 0.6, "stiff": 0.4}
    r = lamina.homogenize(cell, tol=1e-8, threads=1)
    exact = exact_laminate([isotropic(1e9, 0.3), isotropic(20e9, 0.2)], [0.6, 0.4])
    # whole voxel layers make the discrete cell problem exact: what is left
    # is the solver's residual (1e-8, its error in C quadratic in it) and
    # round-off, far below 1e-9 of max |C|
    assert np.abs(r.C - exact).max() <= 1e-9 * np.abs(exact).max()
    assert r.density == pytest.approx(0.6 * 1000 + 0.4 * 3000, rel=1e-15)
    # the layered medium's signature: Reuss-like across, Voigt-like along
    assert r.C[0, 0] < r.C[1, 1] and r.C[3, 3] < r.C[4, 4]


def bulk_shear(E, nu):
    return E / (3 * (1 - 2 * nu)), E / (2 * (1 + nu))


def hs_bulk(K1, G1, K2, f1, f2):
    """Hashin-Shtrikman bulk bound with phase 1 as the reference."""
    return K1 + f2 / (1 / (K2 - K1) + 3 * f1 / (3 * K1 + 4 * G1))


def hs_shear(K1, G1, G2, f1, f2):
    """Hashin-Shtrikman shear bound with phase 1 as the reference."""
    return G1 + f2 / (1 / (G2 - G1) + 6 * f1 * (K1 + 2 * G1) / (5 * G1 * (3 * K1 + 4 * G1)))


def test_sphere_cell_within_hashin_shtrikman(source_dir):
    cell = lamina.Cell.from_file(source_dir / "cases" / "cells" / "sphere.toml",
                                 set={"cell.resolution": 16})
    C = lamina.homogenize(cell, threads=1).C
    Km, Gm = bulk_shear(156e6, 0.494)  # the cell file's phases
    Ks, Gs = bulk_shear(890e6, 0.491)
    fs = cell.phase_fractions["sphere"]
    fm = cell.phase_fractions["matrix"]
    assert fs == pytest.approx(0.19, abs=0.01)
    # cubic symmetry: one bulk modulus and two shear moduli; the bounds hold
    # for the bulk modulus and for the isotropic averages of the shear
    # moduli (C44 of a simple cubic array alone falls below the lower bound)
    K = (C[0, 0] + 2 * C[0, 1]) / 3
    G44, Gp = C[3, 3], (C[0, 0] - C[0, 1]) / 2
    assert hs_bulk(Km, Gm, Ks, fm, fs) <= K <= hs_bulk(Ks, Gs, Km, fs, fm)
    assert hs_shear(Km, Gm, Gs, fm, fs) <= 5 / (2 / Gp + 3 / G44)
    assert (2 * Gp + 3 * G44) / 5 <= hs_shear(Ks, Gs, Gm, fs, fm)
