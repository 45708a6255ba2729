"""The straight-line baseline: the tether drag the field lumps at the kite.

A straight line from the winch to a kite flying crosswind at V_k moves like a
rod turning about the winch: a point at arc length s moves at V_k s / L, so
the cross-flow drag per unit length is (Roselli 2016, eqs. 4.1-4.3)

    f(s) = 1/2 rho(z) C_d,c(Re) d (V_k s / L)^2,

and the force at the kite with the same moment about the winch is

    F_t = (1 / L) * integral_0^L s f(s) ds.

With rho and C_d,c constant this is the closed form (eq. 4.6)

    F_t = rho C_d,c d L V_k^2 / 8,

which this example reproduces by quadrature, then evaluates with the ISA
atmosphere and the cylinder's C_d,c(Re) (the seed's integral, Tab. 5.1's
straight column) at the seed's lengths.

Run: ``python examples/straight_line.py``.
"""

from fem_tether.performance import straight
from fem_tether.config import load_config

CONSTANT = {"air": {"model": "constant", "density_kg_m3": 1.225},
            "drag": {"model": "constant", "cd": 1.2}}


def main() -> dict:
    cfg = load_config(overrides=CONSTANT)
    integral_N = straight.from_config(cfg).drag_N
    closed_N = straight.closed_form_drag_N(1.225, 1.2, cfg.tether.diameter_m, cfg.tether.length_m,
                                           cfg.kite.speed_mps)
    seed_case = load_config()                       # ISA and C_d,c(Re)
    by_length_N = {L: straight.from_config(seed_case.with_length(L)).drag_N for L in (500.0, 1000.0, 3000.0)}
    return {"integral_N": integral_N, "closed_form_N": closed_N, "isa_cylinder_N": by_length_N}


if __name__ == "__main__":
    result = main()
    print(f"constant rho and C_d, L = 1000 m: integral {result['integral_N']:.1f} N, "
          f"closed form (eq. 4.6) {result['closed_form_N']:.1f} N")
    for length, drag in result["isa_cylinder_N"].items():
        print(f"ISA, C_d,c(Re), L = {length:6.0f} m: F_t = {drag:8.1f} N per line")
