"""One version of each concept (issue 21 item 5): the parameters' resolution, the time symbol,
is_zero's proof and its one numeric fallback."""

import sympy as sp

from robosolve.core.parameters import resolve_parameters
from robosolve.core.simplify import is_zero
from robosolve.core.symbols import TIME
from robosolve.load.loader import load_problem_text

a, b, c, d = sp.symbols("a b c d")
PARAMS = {a: sp.Integer(1), b: 2 * a, c: None, d: c + b}


def test_resolution_in_passes_overrides_and_varied():
    assert resolve_parameters(PARAMS) == {a: 1, b: 2}                 # d depends on a null
    assert list(resolve_parameters({b: 2 * a, a: sp.Integer(3)})) == [a, b]   # in resolution order
    assert resolve_parameters(PARAMS, {a: sp.Integer(5), sp.Symbol("q"): 1}) == {a: 5, b: 10}
    assert resolve_parameters(PARAMS, varied={a}) == {a: a, b: 2 * a}
    assert resolve_parameters(PARAMS, {a: sp.Integer(3)}, varied={a}) == {a: 3, b: 6}


def test_the_loader_uses_the_one_time_symbol():
    from conftest import PROBLEMS

    p = load_problem_text((PROBLEMS / "pendulum-runs.yaml").read_text(), "pendulum-runs.yaml")
    law = next(q for q in p.questions if q.id == "sine-motor").options["actuators"]
    syms = set().union(*[sp.sympify(e).free_symbols for e in law.values()])
    assert TIME in syms and sp.Symbol("t") not in syms       # real=True: identity matters
    assert TIME.is_real


def test_is_zero_proves_and_falls_back_only_on_numbers():
    x, y = sp.symbols("x y")
    assert is_zero(sp.sin(x) ** 2 + sp.cos(x) ** 2 - 1)             # the ring's normal form
    assert is_zero(sp.sqrt(x ** 2 + 2 * x * y + y ** 2) ** 2 - (x + y) ** 2)   # simplify
    assert not is_zero(sp.sin(x) - sp.cos(x))
    assert not is_zero(sp.Float(0.3) * x - x / 3)
    assert is_zero(sp.Float(0.5) * x - x / 2)
    assert is_zero(sp.sqrt(2) * sp.sqrt(3) - sp.sqrt(6)) and not is_zero(sp.pi - sp.Rational(355, 113))
    assert is_zero(sp.Integer(0)) and not is_zero(sp.zoo)
    # a point that is 0 only at one point is not identically 0 (no probing of symbols)
    assert not is_zero((x - sp.Rational(3, 10)) * (x - sp.Rational(101, 100)) * (x - sp.Rational(172, 100)))
