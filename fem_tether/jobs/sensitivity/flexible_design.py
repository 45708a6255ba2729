"""The 3 MW AEP design with the FE tether in its loop, as the model of a global sensitivity analysis.

Trevisi's analysis (*Configuration optimisation of kite-based wind turbines*
§5.7) lumps the tether's drag into the kite's with a scalar C_⊥ (eq. 3.14,
Table 5.4: 0.6–1.2).  Here each sample is first the thesis' design
(:func:`fem_tether.uncertainty.kite_design.multistart`: the best of N_max
converged starts), then the loop of :mod:`fem_tether.jobs.design.loop` from
it: the FE line flies every wind bin at the design's operating point, its
drag over the straight rod's multiplies eq. 3.14's, the design is
re-optimised, until the AEP changes by less than the loop's tolerance, and
the FE <-> FD gate checks the most bent bin.  The attribution's flights are
left out (a sample needs the design, not where its AEP went).

The inputs (:data:`UNCERTAIN`) are Table 5.4's parameters that set the line:
the safety factor on its strength (its diameter d), C_⊥ (its drag), the line
voltage (the conductors it carries) and h_min (its length r through the
altitude); the other twelve stay at their nominal values.  The outputs are
:mod:`~fem_tether.uncertainty.kite_design`'s for the flexible design, the
same four of the lumped design it started from (``lumped_*``), so that one
analysis ranks the inputs for both tether models on the same samples, and
what the loop measured: the drag factor's range, its rounds, its FE runs and
whether the gate passed.

One sample runs on one rank (its loop over ``MPI.COMM_SELF``), its bins' parts
in a temporary folder that is removed after it.
"""

from __future__ import annotations

import math
import tempfile
from collections.abc import Mapping
from pathlib import Path

from fem_tether.core.errors import SolverDivergedError
from fem_tether.design.optimiser import Problem, starts_for
from fem_tether.design.result import design_result, record
from fem_tether.jobs.design.flexible import FlexibleSettings
from fem_tether.jobs.design.job import DesignJob
from fem_tether.jobs.design.loop import run_flexible
from fem_tether.uncertainty import kite_design
from fem_tether.uncertainty.kite_design import QUANTITIES, VARIABLES, multistart, parameters

#: Table 5.4's parameters that set the tether
TETHER_INPUTS = ("tether_safety_factor", "cd_perp", "line_voltage_V", "min_altitude_m")
UNCERTAIN = tuple(x for x in kite_design.UNCERTAIN if x.name in TETHER_INPUTS)
#: the lumped design's outputs kept beside the flexible one's
LUMPED = ("aep_Wh", "tether_length_m", "tether_diameter_m", "elevation_rad")
#: what the loop measured
LOOP = {"drag_factor_min": "-", "drag_factor_max": "-", "rounds": "-", "fe_runs": "-", "gate_passed": "-",
        "loop_converged": "-"}
OUTPUT_UNITS = (QUANTITIES | VARIABLES | {f"lumped_{name}": (QUANTITIES | VARIABLES)[name] for name in LUMPED}
                | LOOP | {"starts_tried": "-", "starts_converged": "-"})
#: the outputs that get Sobol' indices: the AEP, the line (r, d, β) and the mass, flexible and lumped
INDEXED = ("aep_Wh", "tether_length_m", "tether_diameter_m", "elevation_rad", "total_mass_kg",
           *(f"lumped_{name}" for name in LUMPED))


def design(sampled: Mapping[str, float]) -> dict[str, float]:
    """One sample: the lumped multistart design at the nominal parameters with ``sampled`` ones set,
    then the flexible loop from it; :data:`OUTPUT_UNITS`.  SolverDivergedError where either finds
    no design."""
    from mpi4py import MPI

    chosen = parameters(sampled)
    problem = Problem(chosen)
    solution, tried, converged = multistart(problem, starts_for(chosen.cl_max))
    lumped = design_result(problem, [solution], [record(0, solution, chosen)], seed=0)
    job = DesignJob(chosen, {}, {}, starts=tried, seed=0, tether="flexible", text="",
                    name="sensitivity sample", flexible=FlexibleSettings())
    with tempfile.TemporaryDirectory(prefix="fem-tether-sample-") as folder:
        outcome = run_flexible(MPI.COMM_SELF, job, Path(folder) / "sample.h5", lumped, progress=False,
                               attribute=False)
    loop = outcome.flexible if outcome is not None else None
    if loop is None or not loop.found or loop.design is None:
        raise SolverDivergedError(f"the flexible loop found no design ({loop.error if loop else 'no outcome'})")
    final = loop.design
    out = {name: float(final.outputs[name]) for name in QUANTITIES}
    out |= {name: float(final.design[name]) for name in VARIABLES}
    out |= {f"lumped_{name}": float(lumped.outputs[name] if name in QUANTITIES else lumped.design[name])
            for name in LUMPED}
    last = loop.rounds[-1] if loop.rounds else {}
    out |= {"drag_factor_min": float(last.get("factor_min", math.nan)),
            "drag_factor_max": float(last.get("factor_max", math.nan)),
            "rounds": float(len(loop.rounds)), "fe_runs": float(loop.fe_runs),
            "gate_passed": float(loop.checked), "loop_converged": float(loop.status == "converged"),
            "starts_tried": float(tried), "starts_converged": float(converged)}
    return {name: out.get(name, math.nan) for name in OUTPUT_UNITS}
