"""Every call that takes an impact speed refuses one that is NaN, infinite, negative or zero with
a ValueError naming the argument, instead of answering e_n = 1."""

import math

import pytest

import mdr_dem

BAD = [math.nan, math.inf, -math.inf, -1.0, 0.0]


@pytest.mark.parametrize("v", BAD)
@pytest.mark.parametrize(
    "call, argument",
    [
        (lambda v: mdr_dem.MdrLaw().restitution(v), "v0"),
        (lambda v: mdr_dem.MdrLaw().restitution([1.0, v]), "v0"),
        (lambda v: mdr_dem.MdrLaw().impact(v), "v0"),
        (lambda v: mdr_dem.curve([1.0, v]), "v0"),
        (lambda v: mdr_dem.curve([v], law="thornton"), "v0"),
        (lambda v: mdr_dem.curve([v], law="hertz"), "v0"),
        (lambda v: mdr_dem.oblique(v), "speed"),
        (lambda v: mdr_dem.fit([0.5, 1.0, v, 4.0], [0.8, 0.7, 0.6, 0.5], free=["scale"]), "v0"),
    ],
)
def test_bad_impact_speed_is_refused_by_name(call, argument, v):
    with pytest.raises(ValueError, match=f"`{argument}`"):
        call(v)


@pytest.mark.parametrize("v", BAD)
def test_fitted_model_refuses_a_bad_speed(v):
    result = mdr_dem.fit([0.5, 1.0, 2.0, 4.0], [0.8, 0.7, 0.6, 0.5], free=["scale"])
    with pytest.raises(ValueError, match="`v0`"):
        result.predict([1.0, v])
