"""lamina.drive of a law given as a dict against numbers from outside the
code: an isotropic elastic law in uniaxial strain with small kinematics
gives sigma_xx = (lambda + 2 mu) eps and sigma_yy = sigma_zz = lambda eps
(Lame's constants of E and nu), no shear stress and no lateral strain."""

import lamina
import numpy as np
import pytest


@pytest.mark.parametrize("E,nu", [(2.1e11, 0.3), (3.0e9, 0.45), (1.0e6, -0.2)])
def test_uniaxial_strain_stress_is_lame(E, nu):
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    d = lamina.drive({"law": "isotropic", "E": E, "nu": nu}, path="uniaxial-strain", rate=1.0,
                     to=0.01, steps=10, kinematics="small")
    # the driven strain e_k = to * k / steps, as eps_xx = F_xx - 1 = (1 + e_k) - 1:
    # rounded to the spacing of doubles near 1 (2.2e-16), hence the 1e-15
    e = 0.01 * np.arange(11) / 10
    np.testing.assert_allclose(d["eps_xx"], e, rtol=0, atol=1e-15)
    # t = k dt with dt = to / rate / steps: two roundings
    np.testing.assert_allclose(d["t"], e / 1.0, rtol=1e-15, atol=0)
    eps = d["eps_xx"]  # the strain the law was given: the stress is exact for it
    for name in ("eps_yy", "eps_zz", "eps_xy", "eps_yz", "eps_xz", "sig_xy", "sig_yz",
                 "sig_xz"):
        assert not d[name].any(), name
    # Round-off only: lambda, mu and the stiffness entries each take a few
    # roundings in either code (different but equivalent formulas), so the
    # stresses agree to a few ulps; 1e-14 relative is some 45 ulps.
    scale = (lam + 2 * mu) * 0.01
    np.testing.assert_allclose(d["sig_xx"], (lam + 2 * mu) * eps, rtol=0, atol=1e-14 * scale)
    np.testing.assert_allclose(d["sig_yy"], lam * eps, rtol=0, atol=1e-14 * scale)
    np.testing.assert_allclose(d["sig_zz"], lam * eps, rtol=0, atol=1e-14 * scale)
    assert d["sig_xx"][-1] > d["sig_yy"][-1] != 0  # not an empty comparison
