#!/usr/bin/python3
"""Every picture script of scripts/ (plot_*.py), run on tiny inputs that the
built programs make in a temporary folder, prints "wrote PATH" for each file
it writes, and only for those: each announced PNG exists and is a non-empty
PNG, no PNG appears that it did not announce, and none is written into the
source tree (default outputs go to the current folder or beside the input).

Usage: plot_scripts_test.py SOURCE_DIR BIN_DIR
The inputs: a 8^3 phase map (micro), two short material-point drives
(materials drive), 20-step membrane runs (Table 1 on an 8 x 8 mesh, the
polyurea sheet, the blast roof with and without drag, the laminate pulse on
90 elements) and a 4^3 reduced-order study (homogenize, materials drive).
A few seconds in all."""
import os
import subprocess
import sys
import tempfile

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
PY = "/usr/bin/python3"


class Failure(Exception):
    pass


def pngs(root):
    """{path: mtime_ns} of every PNG under root (build folders and .git left out)."""
    found = {}
    for d, dirs, files in os.walk(root):
        dirs[:] = [x for x in dirs if not (x.startswith("build") or x.startswith("."))]
        for f in files:
            if f.endswith(".png"):
                p = os.path.join(d, f)
                found[p] = os.stat(p).st_mtime_ns
    return found


def run(cmd, cwd, env):
    done = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)
    if done.returncode != 0:
        raise Failure("%s exited %d:\n%s%s" % (" ".join(cmd), done.returncode, done.stdout,
                                               done.stderr))
    return done.stdout


def check_script(src, tmp, env, args, expected):
    """Run scripts/ARGS[0] with ARGS[1:] in tmp; EXPECTED: the files (relative
    to tmp) it must announce with "wrote PATH"."""
    script = os.path.join(src, "scripts", args[0])
    before_tmp, before_src = pngs(tmp), pngs(src)
    out = run([PY, script] + args[1:], tmp, env)
    announced = set()
    for line in out.splitlines():
        if line.startswith("wrote "):
            announced.add(os.path.realpath(os.path.join(tmp, line[len("wrote "):].strip())))
    want = {os.path.realpath(os.path.join(tmp, e)) for e in expected}
    if announced != want:
        raise Failure("%s: announced %s, expected %s\n%s" % (args[0], sorted(announced),
                                                          sorted(want), out))
    for path in want:
        if path.endswith(".png"):
            with open(path, "rb") as fh:
                head = fh.read(8)
            if head != PNG_SIGNATURE or os.path.getsize(path) < 1000:
                raise Failure("%s: %s is not a non-empty PNG" % (args[0], path))
    after = pngs(tmp)
    written = {os.path.realpath(p) for p, t in after.items() if before_tmp.get(p) != t}
    silent = written - announced
    if silent:
        raise Failure("%s wrote %s without a \"wrote\" line" % (args[0], sorted(silent)))
    changed = {p for p, t in pngs(src).items() if before_src.get(p) != t}
    if changed:
        raise Failure("%s wrote into the source tree: %s" % (args[0], sorted(changed)))
    print("ok %s: %s" % (args[0], ", ".join(sorted(expected))))


def membrane(src, bn, tmp, env, case, out, *sets):
    cmd = [os.path.join(bn, "membrane"), "run", os.path.join(src, "cases", case), "--out", out]
    for s in sets:
        cmd += ["--set", s]
    run(cmd, tmp, env)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src, bn = (os.path.realpath(p) for p in sys.argv[1:3])
    cases = os.path.join(src, "cases")
    with tempfile.TemporaryDirectory(prefix="lamina-plots-") as tmp:
        env = dict(os.environ, OMP_NUM_THREADS="1", XDG_DATA_HOME=tmp,
                   LAMINA_LIBRARY=os.path.join(tmp, "library.toml"), MPLBACKEND="Agg")
        try:
            run([os.path.join(bn, "micro"), os.path.join(cases, "cells", "polyurea.toml"),
                 "--resolution", "8", "--out", "cell.h5"], tmp, env)
            check_script(src, tmp, env, ["plot_cell.py", "cell.h5"], ["cell.png"])
            check_script(src, tmp, env, ["plot_cell.py", "cell.h5", "c.png", "a title"],
                         ["c.png"])

            drive = ["--materials", os.path.join(bn, "materials"), "--steps", "5"]
            check_script(src, tmp, env, ["plot_drive.py", "polyurea-gvbo", "--path", "shear",
                                         "--to", "0.1", "--rates", "1,1e3"] + drive,
                         ["polyurea-gvbo-shear.png"])
            run([os.path.join(bn, "materials"), "drive", "polyurea-gvbo", "--path", "confined",
                 "--rate", "1e3", "--to", "0.1", "--steps", "5", "--out", "d.csv"], tmp, env)
            check_script(src, tmp, env, ["plot_drive.py", "--csv", "d.csv:GVBO", "--path",
                                         "confined"], ["curves-confined.png"])

            membrane(src, bn, tmp, env, "membrane/table1-anisotropic.toml", "t1",
                     "mesh.nx=8", "time.t_end=2e-5")
            check_script(src, tmp, env, ["plot_run.py", "t1", "--title", "table 1"],
                         ["t1/speed.png", "t1/probes.png"])

            membrane(src, bn, tmp, env, "membrane/polyurea-sheet-impact.toml", "imp/elastic",
                     "time.t_end=2e-5", "section[0].material=polyurea-elastic-rest")
            check_script(src, tmp, env, ["plot_impact.py", "imp/elastic"],
                         ["imp/impact-velocity.png"])

            membrane(src, bn, tmp, env, "membrane/blast-roof.toml", "roof", "time.t_end=2e-3")
            check_script(src, tmp, env, ["plot_roof.py", "roof", "--image", "roof.png"],
                         ["roof/roof-side.png", "roof/roof-history.png", "roof.png"])

            lam = os.path.join(cases, "cells", "laminate.toml")
            run([os.path.join(bn, "homogenize"), lam, "--name", "steel-pu-laminate", "--quiet"],
                tmp, env)
            pulse = ("mesh.nx=90", "time.t_end=1e-5")
            membrane(src, bn, tmp, env, "membrane/laminate-pulse.toml", "on", *pulse)
            membrane(src, bn, tmp, env, "membrane/laminate-pulse.toml", "off", *pulse,
                     "section[0].micro_inertia=false")
            check_script(src, tmp, env, ["plot_dispersion.py", "on", "off", "--cell", lam],
                         ["laminate-pulse.png"])

            check_script(src, tmp, env, ["plot_rom.py", "--cell",
                                         os.path.join(cases, "cells", "polyurea-two-scale.toml"),
                                         "--partitions", "1", "--rates", "1e3", "--paths", "shear",
                                         "--to", "0.05", "--steps", "3", "--resolution", "4",
                                         "--bin", bn, "--work", "rom", "--out", "rom.png"],
                         ["rom.png", "rom/table.md"])
        except Failure as e:
            sys.exit("FAIL: %s" % e)
    covered = {"plot_cell.py", "plot_drive.py", "plot_run.py", "plot_impact.py", "plot_roof.py",
               "plot_dispersion.py", "plot_rom.py"}
    every = {f for f in os.listdir(os.path.join(src, "scripts"))
             if f.startswith("plot_") and f.endswith(".py")}
    if every - covered:
        sys.exit("FAIL: no tiny input for %s: add one here" % sorted(every - covered))
    print("every plot script announced exactly the files it wrote")


if __name__ == "__main__":
    main()
