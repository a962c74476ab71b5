#!/usr/bin/python3
"""A membrane run from Python whose probe history is plotted: case 1 of the
membrane paper (cases/membrane/case1.toml, a step load on the centre of a
square membrane fixed on its edges).

    PYTHONPATH=build/python /usr/bin/python3 examples/membrane_probe.py --out out/probes

The deflection front travels at the transverse shear wave speed
sqrt(G / rho) (isotropic: D66 = G); the dashed line marks when it reaches
the quarter probe from the edge of the loaded square.
"""
import argparse
import math
import pathlib
import tomllib

import matplotlib

import lamina

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend)

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", default=ROOT / "cases" / "membrane" / "case1.toml")
    parser.add_argument("--out", default=".", help="folder of probes.png")
    parser.add_argument("--small", action="store_true", help="tiny sizes (CI)")
    args = parser.parse_args()
    overrides = {"time.t_end": 2e-4} if args.small else {}  # small: 20 steps

    result = lamina.membrane.run(args.case, set=overrides)
    probes = result.probes  # column -> array: t, centre_ux, ..., quarter_vz
    print(f"{len(probes['t'])} steps written, max |w| = {result.summary['max_abs_w']:.4g} m")

    with open(args.case, "rb") as f:
        case = tomllib.load(f)
    section = case["section"][0]
    speed = math.sqrt(section["E"] / (2 * (1 + section["nu"])) / section["density"])
    quarter = next(p for p in case["probe"] if p["name"] == "quarter")
    arrival = (case["load"][0]["box"][0] - quarter["at"][0]) / speed

    fig, ax = plt.subplots(figsize=(6, 4))
    for name in ("centre", "quarter"):
        ax.plot(probes["t"] * 1e3, probes[name + "_uz"] * 1e3, label=name)
    ax.axvline(arrival * 1e3, ls="--", c="grey", label=f"front at quarter ({speed:.0f} m/s)")
    ax.set(xlabel="t (ms)", ylabel="w (mm)", title=pathlib.Path(args.case).name)
    ax.legend()
    fig.tight_layout()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fig.savefig(out / "probes.png", dpi=120)
    print("wrote", out / "probes.png")


if __name__ == "__main__":
    main()
