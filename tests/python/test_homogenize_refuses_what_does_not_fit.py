"""lamina.homogenize refuses, before it allocates, a cell whose solve does
not fit in the memory the process may use, as the homogenize program does:
a lamina.InputError with the amount, never the interpreter killed by the
out-of-memory handler. The limit is set with RLIMIT_AS in a child process
(core::availableMemoryBytes honours it), so the test does not depend on
the machine's memory."""

import re
import subprocess
import sys

CHILD = r"""
import resource, sys
import numpy as np
limit = 3 << 30
resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
import lamina
labels = np.zeros((256, 256, 256), dtype=np.int32)
labels[:128] = 1
phases = {0: {"name": "matrix", "law": "isotropic", "E": 3e9, "nu": 0.35, "density": 1200.0},
          1: {"name": "fibre", "law": "isotropic", "E": 70e9, "nu": 0.2, "density": 2500.0}}
cell = lamina.Cell.from_array(labels, phases, size=1e-4)
try:
    lamina.homogenize(cell, threads=1)
except lamina.InputError as e:
    print(str(e))
    sys.exit(0)
sys.exit("homogenize was not refused")
"""


def test_a_cell_beyond_the_memory_limit_is_refused_with_the_amount():
    proc = subprocess.run([sys.executable, "-c", CHILD], capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr + proc.stdout
    message = proc.stdout.strip()
    assert "homogenizing 256 x 256 x 256 voxels needs about" in message, message
    amount = re.search(r"needs about ([0-9.]+) GiB", message)
    assert amount, message
    # docs/homogenize-solver.md, "Memory": at the default tol 1e-5 232 to 244
    # bytes per voxel of solver fields, 8 of phase map on rank 0 and 180 of
    # dispersion spectra for a cell with a size: 420 to 432 bytes per voxel,
    # 6.56 to 6.75 GiB at 256^3 (printed to two digits: 6.5 to 6.8)
    assert 6.5 <= float(amount.group(1)) <= 6.8, message
