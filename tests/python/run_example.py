"""Runs one script of examples/ as CI does (tests/python/CMakeLists.txt):
with --small, in a temporary folder that is also its --out. Exits non-zero
unless the script exits 0 and leaves a PNG picture there (by its signature).

Usage: run_example.py EXAMPLE.py
"""
import pathlib
import subprocess
import sys
import tempfile

PNG = b"\x89PNG\r\n\x1a\n"


def main():
    script = pathlib.Path(sys.argv[1]).resolve()
    with tempfile.TemporaryDirectory(prefix="lamina-example-") as out:
        code = subprocess.run([sys.executable, str(script), "--small", "--out", out],
                              cwd=out).returncode
        if code != 0:
            print(f"{script.name} --small exited {code}")
            return 1
        pictures = [p.name for p in pathlib.Path(out).glob("*.png")
                    if p.read_bytes()[:8] == PNG]
        if not pictures:
            print(f"{script.name} --small wrote no PNG picture into --out")
            return 1
        print(f"{script.name} --small: {', '.join(pictures)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
