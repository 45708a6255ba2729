"""Peak memory of the process: in MiB, it never decreases, and it sees a large array."""

import subprocess
import sys

from fem_tether.memory import peak_rss_MiB

GROWTH = """
import numpy as np
from fem_tether.memory import peak_rss_MiB
before = peak_rss_MiB()
block = np.ones(256 * 2**20 // 8)           # 256 MiB, touched
print(before, peak_rss_MiB())
"""


def test_peak_rss_never_falls():
    first = peak_rss_MiB()
    assert 10.0 < first <= peak_rss_MiB()


def test_peak_rss_sees_a_touched_256_MiB_array():
    """In a fresh process a 256 MiB array raises the
    peak by more than half of it (the peak of the imports may exceed what stays
    resident after them; 256 MiB is well above that)."""
    out = subprocess.run([sys.executable, "-c", GROWTH], capture_output=True, text=True, check=True)
    before, after = map(float, out.stdout.split())
    assert after - before > 128.0
