"""The models a sensitivity job can name (fem_tether.jobs.sensitivity.models): each exposes what the job
and the analysis need, and an unknown name is refused naming the known ones."""

import pytest

from fem_tether.core.errors import InputError
from fem_tether.uncertainty import cantilever
from fem_tether.uncertainty.inputs import Input
from fem_tether.jobs.sensitivity.models import MODELS, model


def test_cantilever_is_registered_as_its_module():
    assert model("cantilever") is cantilever


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_model_exposes_inputs_with_sources_outputs_indexed_and_design(name):
    """Its inputs are Inputs with a source and unique names; its indexed outputs are among its
    outputs; its design is callable."""
    m = model(name)
    assert m.UNCERTAIN and all(isinstance(x, Input) and x.source for x in m.UNCERTAIN)
    assert len({x.name for x in m.UNCERTAIN}) == len(m.UNCERTAIN)
    assert m.INDEXED and set(m.INDEXED) <= set(m.OUTPUT_UNITS)
    assert callable(m.design) and callable(m.parameters)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_model_checks_its_parameters(name):
    """Its inputs' means are accepted; its first input far out of range is refused, a ValueError naming it
    (the job checks every sample with it before any evaluation)."""
    m = model(name)
    m.parameters({x.name: x.distribution.mean for x in m.UNCERTAIN})
    first = m.UNCERTAIN[0].name
    with pytest.raises(ValueError, match=f"^{first} = -1e\\+30: must be"):
        m.parameters({first: -1e30})


def test_the_cantilever_indexes_table_4_4s_varying_outputs():
    """Every output of Table 4.4 but the stress multiplier (0 at every design of §4.3)."""
    assert set(cantilever.OUTPUT_UNITS) - set(cantilever.INDEXED) == {"stress_multiplier_kg"}


def test_an_unknown_model_is_refused_naming_the_known():
    with pytest.raises(InputError) as raised:
        model("kite")
    assert str(raised.value) == f"model = 'kite': unknown (one of {', '.join(sorted(MODELS))})"
    assert "cantilever, trevisi-3mw, trevisi-3mw-30m2" in str(raised.value)
