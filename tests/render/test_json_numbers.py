"""results.json's number policy: 12 significant digits, and wrapped angles kept in their interval."""

from __future__ import annotations

import math

from robosolve.questions.registry import QUESTION_TYPES
from robosolve.render.numbers import json_angle, json_number
from robosolve.render.results_json import numeric_value


def test_twelve_digits_would_carry_pi_out_of_its_interval_but_an_angle_stays_in():
    assert json_number(math.pi) > math.pi            # the plain rule rounds up ...
    for x in (math.pi, math.pi - 3e-13, -math.pi + 1e-14):
        a = json_angle(x)
        assert -math.pi < a <= math.pi and abs(math.cos(a) - math.cos(x)) < 1e-12
    assert json_angle(3.0) == 3.0 and json_angle(-2.5) == -2.5
    assert json_angle(-3.14159265358) == -3.14159265358


def test_ik_solutions_in_results_json_are_inside_minus_pi_pi():
    key = QUESTION_TYPES["inverse_kinematics"].key("solutions")
    sols = [{"q1": 0.5, "q4": math.pi}, {"q1": -math.pi + 2e-15, "q4": 1.0}]
    out = numeric_value(sols, key)
    for s in out:
        for v in s.values():
            assert -math.pi < v <= math.pi
    assert out[0]["q1"] == 0.5 and out[1]["q4"] == 1.0
