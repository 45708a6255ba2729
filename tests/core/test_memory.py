"""Peak memory of the process: in MiB, it never decreases, and it sees a large array."""

import subprocess
import sys

from fem_tether.core.memory import peak_rss_MiB

GROWTH = """
import numpy as np
from fem_tether.core.memory import peak_rss_MiB
before = peak_rss_MiB()
block = np.ones(256 * 2**20 // 8)           # 256 MiB, touched
print(before, peak_rss_MiB())
"""


def test_peak_rss_never_falls():
    first = peak_rss_MiB()
    assert 10.0 < first <= peak_rss_MiB()


def test_peak_rss_sees_a_touched_256_MiB_array_in_MiB():
    """A process holding a touched 256 MiB array reports a peak above 256 MiB
    and well below 4 GiB (a KiB/byte mix-up would be off by 1024).  Only bounds:
    on Linux a child's peak starts at its parent's (``ru_maxrss`` survives exec)."""
    out = subprocess.run([sys.executable, "-c", GROWTH], capture_output=True, text=True, check=True)
    before, after = map(float, out.stdout.split())
    assert before <= after and 256.0 < after < 4096.0
