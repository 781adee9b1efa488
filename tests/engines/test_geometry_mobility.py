"""Gruebler / Kutzbach counts, with the seed's examples as corrected (ERRATA 3-5)."""

import pytest

from robosolve.geometry.mobility import gruebler, kutzbach, mobility


def test_seed_serial_robot():
    # seed §1.1.3: 4 links + base, 4 revolute joints -> 4 (ERRATA item 4)
    r = gruebler(5, 4)
    assert r.dof == 4 and r.status == "mechanism"
    assert r.substituted == "n = 3(5 - 1) - 2·4 - 0"
    assert kutzbach(5, 4).dof == 4  # the spatial 4R count agrees


def test_seed_five_bar_has_two_dof():
    # ERRATA item 5: 3(5-1) - 2*5 = 2, not 3
    assert gruebler(5, 5).dof == 2


def test_classic_mechanisms():
    assert gruebler(4, 4).dof == 1  # four-bar
    assert gruebler(6, 7).dof == 1  # Watt / Stephenson six-bar
    assert gruebler(3, 2, 1).dof == 1  # cam with follower: two pins and a cam contact
    # Stewart platform: base + platform + 6 two-part legs, 6 P, 6 U, 6 S
    assert kutzbach(14, 6, 6, 6).dof == 6


def test_structure_and_overconstrained_warnings():
    r = gruebler(3, 3)  # triangle
    assert r.dof == 0 and r.status == "structure" and r.notes
    r = gruebler(4, 5)
    assert r.dof == -1 and r.status == "overconstrained" and "over-constrained" in r.notes[0]
    r = kutzbach(4, 4)  # a planar four-bar counted in space: -2, mobile only by geometry
    assert r.dof == -2 and r.status == "overconstrained"


def test_terms_add_up():
    r = kutzbach(7, 3, 2, 1)
    assert sum(v for _, v in r.terms) == r.dof == 6 * 6 - 15 - 8 - 3


@pytest.mark.parametrize("args,kw", [
    ((0,), {}), ((-1, 0), {}), ((3, -1), {}), ((3, 1.5), {}), ((3, True), {}),
    ((3, 1, 0, 1), {"space": "planar"}), ((3, 1), {"space": "plane"}),
])
def test_bad_input(args, kw):
    with pytest.raises(ValueError):
        mobility(*args, **kw)
