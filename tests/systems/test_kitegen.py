"""The KiteGen as operating points (fem_tether.systems.kitegen): its zones come in their order."""

import re
from dataclasses import replace

import numpy as np
import pytest

from fem_tether.config import load_config
from fem_tether.physics.kite import KiteGenDesign, characteristic_curves, characteristic_speeds
from fem_tether.systems.kitegen import KiteGenSystem, check_zones

#: the wing of the M600 flown as a KiteGen at its unrated 179 m/s: what `curves --system makani-m600`
#: drew before issue 29 (cut-in 4.47 m/s after full-force 2.75 m/s)
FAST = dict(area_m2=35.0, cl=2.0, efficiency=40.0, kite_efficiency=40.0, speed_mps=179.0, theta_rad=1.0, phi_rad=0.0)


def design(**fields) -> KiteGenDesign:
    return replace(KiteGenDesign.from_config(load_config().kite, 2), **fields)


def test_the_seed_case_has_its_zones_in_order():
    """Roselli §2.4: cut-in 2.86 m/s, full-force 3.63 m/s (Tab. 5.3's)."""
    seed = design()
    speeds = characteristic_speeds(seed)
    assert (round(float(speeds.cut_in_mps), 2), round(float(speeds.full_force_mps), 2)) == (2.86, 3.63)
    assert check_zones(seed) is seed


def test_a_cut_in_above_the_full_force_wind_is_refused_and_the_bounds_it_names_order_the_zones():
    """Cut-in V_k/E above V_ff: at cut-in the held lines would pull C (V_k sinϑ cosφ/E)² > F_n, and
    the seed's zones jump from off to reel-out (zone B empty, power from the cut-in on).  The error
    names the keys; the speed_mps and nominal_force_N it gives put the cut-in on V_ff (1e-3)."""
    fast = design(**FAST)
    curves = characteristic_curves(np.linspace(0.0, 10.0, 1001), fast)
    assert "B" not in set(curves.zone) and curves.power_W[curves.zone != "A"].min() > 0
    with pytest.raises(ValueError, match=r"^\[kite\] speed_mps = 179 m/s, efficiency = 40: the KiteGen cut-in wind "
                                         r"V_k/E = 4\.47 m/s is above the full-force wind 2\.75 m/s") as err:
        check_zones(fast)
    speed, force = map(float, re.search(r"speed_mps <= (\S+) m/s or nominal_force_N >= (\S+) N$",
                                        str(err.value)).groups())
    for fixed in (replace(fast, speed_mps=speed), replace(fast, nominal_force_N=force)):
        s = characteristic_speeds(fixed)
        assert float(s.cut_in_mps) == pytest.approx(float(s.full_force_mps), rel=1e-3)
    with pytest.raises(ValueError, match="cut-in wind"):
        KiteGenSystem(fast, straight_cd=0.01)
