"""The forward-dynamics energy step says what the forces depend on (issue 22): time, the rates or
the other joints, never "time or the rates" when it is the joints."""

from types import SimpleNamespace

import sympy as sp

from robosolve.solvers.forward_dynamics import _no_closed_work


def _joint(name):
    return SimpleNamespace(symbol=sp.Symbol(name, real=True), dot=sp.Symbol(f"{name}_dot", real=True))


def test_the_wording_names_what_the_forces_depend_on():
    q1, q2 = _joint("q1"), _joint("q2")
    model = SimpleNamespace(joints=[q1, q2])
    t = sp.Symbol("t", real=True)
    said = lambda forces: _no_closed_work(model, SimpleNamespace(forces=forces), {})  # noqa: E731
    assert said([q2.symbol, 0]) == "A generalized force depends on the other joints, so the work has no closed form here. "
    assert said([sp.sin(t), q1.dot]) == ("A generalized force depends on time and on the rates, so the work "
                                         "has no closed form here. ")
