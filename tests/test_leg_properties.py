"""Property tests (hypothesis): any leg the Leg class accepts, any foot it can reach."""

import math

from hypothesis import given, settings
from hypothesis import strategies as st

from hexapod.leg import OK, Leg
from hexapod_host.testing import reference

OPEN = (-18000, 18000, -18000, 18000, -18000, 18000)

legs = st.tuples(
    st.integers(0, 1500),  # coxa
    st.integers(100, 2500),  # femur
    st.integers(100, 2500),  # tibia
    st.integers(-1500, 1500),  # femur offset
)
angles = st.tuples(st.floats(-179.0, 179.0), st.floats(-89.0, 89.0), st.floats(-179.0, -1.0))


@settings(max_examples=600, deadline=None, derandomize=True)
@given(legs, angles)
def test_ik_of_a_reached_point_round_trips_and_matches_the_oracle(geometry, t):
    coxa, femur, tibia, off = geometry
    rho = coxa + femur * math.cos(math.radians(t[1])) + tibia * math.cos(math.radians(t[1] + t[2]))
    x, y, z = (round(v) for v in reference.fk(*t, coxa, femur, tibia, off))
    exact = reference.ik(x, y, z, coxa, femur, tibia, off)
    leg = Leg(coxa=coxa, femur=femur, tibia=tibia, femur_offset=off, limits=OPEN)
    out, foot = [0, 0, 0], [0, 0, 0]
    code = leg.ik(x, y, z, out)
    if exact is None or rho <= 0:
        return  # rounding left the workspace, or the foot is behind the coxa axis
    assert code == OK, (x, y, z, code, leg.excess)
    leg.fk(out[0], out[1], out[2], foot)
    assert max(abs(foot[k] - (x, y, z)[k]) for k in range(3)) <= 1
    if math.hypot(math.hypot(x, y) - coxa, z - off) >= 1:
        for k in range(3):
            err = abs(out[k] / 100 - exact[k])
            assert min(err, 360 - err) <= 0.02, (k, out, exact)


@settings(max_examples=300, deadline=None, derandomize=True)
@given(legs, st.integers(-40000, 40000), st.integers(-40000, 40000), st.integers(-40000, 40000))
def test_refusals_leave_out_untouched_and_say_why(geometry, x, y, z):
    coxa, femur, tibia, off = geometry
    leg = Leg(coxa=coxa, femur=femur, tibia=tibia, femur_offset=off)
    out = [11, 22, 33]
    code = leg.ik(x, y, z, out)
    if code != OK:
        assert out == [11, 22, 33]
        assert leg.excess > 0
    else:
        assert -9000 <= out[0] <= 9000 and -9000 <= out[1] <= 9000 and -18000 <= out[2] <= 0
