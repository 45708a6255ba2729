"""The warning record (fem_tether.performance.caveats): what the JSON documents hold."""

import json

from fem_tether.performance.caveats import Caveat
from fem_tether.report.text import caveat_lines, json_text


def test_a_caveat_is_the_same_record_in_json_and_in_text():
    caveat = Caveat("margin-below-safety-factor", "margin below the safety factor 1.2: 1.199 at 1000 m", "margin",
                    (1000.0,))
    record = json.loads(json_text({"warnings": [caveat.as_dict()]}))["warnings"][0]
    assert record == {"code": "margin-below-safety-factor", "quantity": "margin", "lengths_m": [1000.0],
                      "message": "margin below the safety factor 1.2: 1.199 at 1000 m"}
    assert caveat_lines([record]) == ["warning: margin below the safety factor 1.2: 1.199 at 1000 m"]
    assert caveat_lines([record], ("best_length_fe_m",)) == []
