"""fem_tether.config.settings: values written as TOML read back as themselves."""

import tomllib

import pytest

from fem_tether.config.settings import toml_value


@pytest.mark.parametrize("value", [True, 3, 2.5, 1e-05, "a \"quoted\" name", ["kitegen", "ke-yoyo"], (1.0, 2.0),
                                   [[1, 2], ["x"]], [], {"name": "a", "h_m": [10.0, 20.0]}, [{"name": "a"}]])
def test_a_value_reads_back_as_itself(value):
    expected = list(value) if isinstance(value, tuple) else value
    assert tomllib.loads(f"key = {toml_value(value)}")["key"] == expected


def test_a_list_of_names_is_a_toml_array_not_a_python_repr():
    assert toml_value(["kitegen", "ke-yoyo"]) == '["kitegen", "ke-yoyo"]'
