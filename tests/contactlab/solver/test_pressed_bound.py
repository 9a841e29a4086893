"""The bound that lets a compiled contact piece skip a step's contact-end samples.

:func:`contactlab.kernels.power_piece._pressed` skips the nine samples of a step where
the contact force is bounded above zero on the step's interpolant; that is only right if
the bounds hold everywhere on the step, checked here against the interpolant read densely
(:func:`contactlab.kernels.dop853.interpolate`) and the force formula itself.
"""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from contactlab.kernels import power_piece
from contactlab.kernels.dop853 import interpolate
from contactlab.kernels.power import force, force_floor, pack
from contactlab.laws import HertzDamped, HuntCrossley, KuwabaraKono

X = np.linspace(0.0, 1.0, 1001)  # where the interpolant is read densely [-]
COEFFICIENT = st.floats(-1.0, 1.0)


def _dense(F, y_old, i, j):
    out, values = np.empty(y_old.size), []
    for x in X:
        interpolate(F, y_old, x, out)
        values.append(out[j] - out[i])
    return np.array(values)


@settings(deadline=None)  # the first example compiles the kernels
@given(st.lists(COEFFICIENT, min_size=7 * 4 + 4, max_size=7 * 4 + 4))
def test_the_span_holds_the_interpolant(numbers):
    F, y_old = np.array(numbers[:28]).reshape(7, 4), np.array(numbers[28:])
    for i, j in ((0, 2), (1, 3)):
        lo, hi = power_piece._span(F, y_old, i, j)
        values = _dense(F, y_old, i, j)
        slack = 1e-14  # the interpolant's rounding on values of order 1
        assert lo - slack <= values.min() and values.max() <= hi + slack


def test_the_span_is_tight_for_a_chord():
    F, y_old = np.zeros((7, 4)), np.array([0.0, 0.0, 1.0, 3.0])
    F[0] = [0.0, 0.0, 2.0, -1.0]
    assert power_piece._span(F, y_old, 0, 2) == (1.0, 3.0)  # a straight line: its ends
    assert power_piece._span(F, y_old, 1, 3) == (2.0, 3.0)


LAWS = (
    HertzDamped(1.5e6, 4.175),
    KuwabaraKono(1.5e6, 2e-6),
    HuntCrossley(1.5e6, 1.5, 0.2),
)


@settings(deadline=None)  # the first example compiles the kernels
@given(
    st.sampled_from(LAWS),
    st.floats(1e-9, 1e-5),
    st.floats(0.0, 1.0),
    st.floats(-3.0, 3.0),
    st.floats(0.0, 3.0),
)
def test_the_force_floor_is_below_the_force_on_its_box(law, d_lo, stretch, r_lo, widen):
    par = pack(law.power_form(), 1e-3, 6e7, 1.0, 5e-5, False)
    d_hi, r_hi = d_lo * (1.0 + 10.0 * stretch), r_lo + widen
    floor, size = force_floor(d_lo, d_hi, r_lo, r_hi, par)
    forces = [
        force(d, r, par) for d in np.linspace(d_lo, d_hi, 21) for r in np.linspace(r_lo, r_hi, 21)
    ]
    assert floor <= min(forces) * (1 + 1e-12) + 1e-12 * size  # rounding of the formula
    assert max(abs(f) for f in forces) <= size * (1 + 1e-12)  # the same rounding


def test_no_floor_where_the_overlap_can_vanish():
    par = pack(HertzDamped(1.5e6, 4.175).power_form(), 1e-3, 6e7, 1.0, 5e-5, False)
    assert force_floor(0.0, 1e-6, 1.0, 2.0, par)[0] == -np.inf
    assert force_floor(-1e-9, 1e-6, 1.0, 2.0, par)[0] == -np.inf
