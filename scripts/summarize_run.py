#!/usr/bin/python3
"""One-screen text summary of a membrane run.

Usage: /usr/bin/python3 scripts/summarize_run.py RUN_DIR MATERIAL_JSON [--title T]

MATERIAL_JSON is the output of `materials show NAME --json`. Writes
RUN_DIR/summary.txt and prints it. Wave speeds are those of the membrane model
(docs/membrane.md): in-plane P along x sqrt(D11/rho) and along y
sqrt(D22/rho), in-plane shear sqrt(D44/rho), out-of-plane (w) along x
sqrt(D66/rho) and along y sqrt(D55/rho), D in lamina order.
"""
import argparse
import json
import math
import os


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_dir")
    ap.add_argument("material_json")
    ap.add_argument("--title", default="")
    a = ap.parse_args()
    with open(os.path.join(a.run_dir, "summary.json")) as fh:
        s = json.load(fh)
    with open(a.material_json) as fh:
        m = json.load(fh)
    C, rho = m["C"], m["density"]

    def speed(i):
        return math.sqrt(C[i][i] / rho)

    e = s.get("energy", {})
    lines = [
        f"{a.title or s.get('case', '')}",
        f"  material        {m['name']} ({m['kind']}), symmetry {m['symmetry']}, "
        f"anisotropy index {m.get('anisotropy_index', float('nan')):.3g}",
        f"  density         {rho:.6g} kg/m^3"
        + (f", thickness {m['thickness'] * 1e3:.4g} mm" if "thickness" in m else ""),
        f"  P speed         x {speed(0):8.1f} m/s   y {speed(1):8.1f} m/s   (sqrt(D11/rho), sqrt(D22/rho))",
        f"  in-plane shear  {speed(3):8.1f} m/s                       (sqrt(D44/rho))",
        f"  w speed         x {speed(5):8.1f} m/s   y {speed(4):8.1f} m/s   (sqrt(D66/rho), sqrt(D55/rho))",
        f"  mesh            {s['nodes']} nodes, {s['elements']} triangles; {s['steps']} steps of "
        f"{s['dt'] * 1e6:.3g} us to {s['t_end'] * 1e6:.4g} us",
        f"  peak |w|        {s['max_abs_w'] * 1e3:.4g} mm, peak |v| {s['max_speed']:.4g} m/s",
        f"  energy          kinetic {e.get('kinetic', 0):.4g} J, strain {e.get('strain', 0):.4g} J, "
        f"reaction work {e.get('reaction_work', 0):.4g} J",
        f"  energy balance  |E_n - E_0 - W_n| / scale = {e.get('relative_balance', float('nan')):.2e}",
        f"  time            {s['wall_s']:.2f} s wall ({s['step_s'] * 1e3:.2f} ms per step)",
    ]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(a.run_dir, "summary.txt"), "w") as fh:
        fh.write(text)
    print(text, end="")


if __name__ == "__main__":
    main()
