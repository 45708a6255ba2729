"""The point-mass kite on the FE line's free end (docs/free-kite.md): the coupled
Jacobian, the crosswind law's limit, path tracking, the prescribed path's F_t, the
series and the start."""

import numpy as np
import pytest

from fem_tether.config import load_config
from fem_tether.fe.solver import FESolver, add_kite, build_model


def _dense(sys_, ev):
    """The Jacobian of a free-end system as a dense matrix (R's row k_s dR, zero column)."""
    n, m = sys_.n, sys_.n - 1
    A = np.zeros((n, n))
    for j in range(m):
        for i in range(max(0, j - 6), min(m, j + 7)):
            A[i, j] = ev.ab[6 + i - j, j]
    A[:m, -1] = ev.r_col
    A[-1, -1] = ev.k_s
    return A


@pytest.mark.parametrize("kernel", ["compiled", "numpy"])
@pytest.mark.parametrize("polar", [False, True])
def test_coupled_jacobian_matches_central_differences(kernel, polar, tmp_path):
    """ISA, cylinder C_d(Re), De Bilt wind, a 90 kg kite (per line) with roll 10°,
    turbines (gamma_t 0.5) and, in one case, a polar C_L(alpha), C_D(alpha): every
    entry of the coupled Jacobian (line + kite: dF/dr_N, c_v dF/dv_N, dF/dd in
    (N, N) and (N, N-1)) within 1e-6 of the largest against central differences."""
    kite = {"model": "point-mass", "turbine_factor": 0.5}
    if polar:
        path = tmp_path / "polar.csv"
        path.write_text("alpha_deg,cl,cd\n-10,0.2,0.05\n0,0.8,0.06\n10,1.3,0.09\n20,1.5,0.16\n")
        kite |= {"polar": str(path), "base_aoa_deg": 3.0}
    cfg = load_config(overrides={"fe": {"elements": 6, "kernel": kernel}, "kite": kite,
                                 "system": {"kite_mass_kg": 180.0}})
    solver = FESolver(build_model(cfg))
    st = solver.initial_state()
    model = solver.model
    sys_ = model.system
    assert sys_.free_end and st.steer is not None
    rng = np.random.default_rng(1)
    r0 = st.kin.q + rng.normal(size=st.kin.q.shape) * 0.5
    v0 = st.kin.v + rng.normal(size=st.kin.q.shape) * 2
    T, R = st.T * 1.05, st.R
    c_a, c_v, roll = 7.0, 3.0, np.radians(10.0)
    e = model.end.state(0.3, 1.0)[0]

    def evaluation(x, jacobian):
        r, T_, R_ = sys_.unpack(x)
        v, qdd = v0 + c_v * (r - r0), c_a * (r - r0)
        ev = sys_.evaluate(r, v, qdd, T_, R_, e, 0.0, model.radius_m, 1e5, c_a, c_v, jacobian=jacobian)
        add_kite(sys_, ev, model.kite, r, v, roll, c_v)
        return ev

    x = sys_.pack(r0, T, R)
    A = _dense(sys_, evaluation(x, True))
    N = np.zeros_like(A)
    for j in range(x.size):
        dx = np.zeros(x.size)
        dx[j] = 1e-6 * max(1.0, abs(x[j]))
        N[:, j] = (evaluation(x + dx, False).residual - evaluation(x - dx, False).residual) / (2 * dx[j])
    assert np.max(np.abs(A - N)) <= 1e-6 * np.max(np.abs(N))
    assert np.max(np.abs(A[-8:-1, -8:-1] - N[-8:-1, -8:-1])) <= 1e-6 * np.max(np.abs(N[-8:-1, -8:-1]))
