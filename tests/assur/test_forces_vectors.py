"""The test vectors of ``docs/forces.md`` §8: three mechanisms at four crank angles.

The expected values come from the document (an independent formulation: all links'
Newton–Euler equations solved at once with the kinematics at 50 significant digits); each
must be reproduced to 1e-9 of the largest value of the same kind (force, moment, torque).
"""

from __future__ import annotations

import numpy as np
import pytest
from force_tables import load

from assur.forces import kinetostatics
from assur.kinematics.analysis import analyse

ANGLES = np.radians([30.0, 120.0, 210.0, 300.0])
OMEGA = 10.0

VECTOR_A = (
    ('driving torque, N·m', (-30.30620484, -6.103887289, 28.62303311, 7.716136182)),
    ('0-1 x, N', (599.9109926, 610.4113599, 605.2986167, 584.5472202)),
    ('0-1 y, N', (-86.72467601, 50.64429872, 239.4242041, 86.23857732)),
    ('1-2 x, N', (599.9857522, 609.7908472, 605.2238572, 585.1677329)),
    ('1-2 y, N', (-88.55666331, 48.26655824, 236.3511914, 83.7113178)),
    ('2-3 x, N', (600.2135927, 605.4815973, 603.6936143, 590.7373378)),
    ('2-3 y, N', (-95.8846125, 38.75559635, 224.0591406, 73.60227969)),
    ('3-0 x, N', (0.0, 0.0, 0.0, 0.0)),
    ('3-0 y, N', (-110.5996125, 24.04059635, 209.3441406, 58.88727969)),
    ('3-0 normal, N', (-110.5996125, 24.04059635, 209.3441406, 58.88727969)),
    ('3-0 moment, N·m', (0.0, 0.0, 0.0, 0.0)),
)

VECTOR_B = (
    ('driving torque, N·m', (7.246518235, 4.055421806, -2.985726997, -10.10450136)),
    ('A x, N', (-179.4294636, -151.5897487, -73.30373766, -192.6108379)),
    ('A y, N', (-74.54897894, -100.297613, -170.5484703, -250.5409503)),
    ('B x, N', (-179.4312585, -151.9928576, -73.30194275, -192.207729)),
    ('B y, N', (-76.10787005, -102.2614079, -172.9135792, -252.5011554)),
    ('C x, N', (-179.1330894, -153.4431523, -73.97156904, -189.4302595)),
    ('C y, N', (-79.57088798, -107.4915072, -179.2998412, -256.3061865)),
    ('D x, N', (-178.9556572, -153.8770813, -74.40673075, -188.0418994)),
    ('D y, N', (-83.09967662, -111.6665903, -183.626421, -259.5160731)),
)

VECTOR_C = (
    ('driving torque, N·m', (13.4599521, 12.92070366, 2.095910516, 8.210079725)),
    ('0-1 x, N', (-373.2529063, -165.6770618, -113.7045799, -35.87914993)),
    ('0-1 y, N', (27.49625595, -276.3621671, -300.7670238, 258.7032923)),
    ('1-2 x, N', (-373.0529151, -166.0234669, -113.9045711, -35.53274485)),
    ('1-2 y, N', (25.88066103, -278.1241759, -303.0754289, 256.5413011)),
    ('2-3 x, N', (13.22794322, -23.88492007, 20.63956889, 24.51595399)),
    ('2-3 y, N', (-267.6242685, 36.64125918, -4.593998079, -68.32589825)),
    ('3-0 x, N', (17.40150298, -24.73109682, 15.53086515, 25.5103504)),
    ('3-0 y, N', (-272.1369651, 31.47246462, -15.08824728, -72.24816551)),
    ('3-4 x, N', (-3.203187413, 0.2995793796, 4.622203885, -1.264323838)),
    ('3-4 y, N', (-0.1957230978, 0.2168430161, 5.085449313, -0.4586908716)),
    ('3-4 normal, N', (3.209161437, -0.3698225228, -6.872158574, 1.344958023)),
    ('3-4 moment, N·m', (0.003922170478, -0.001881224434, -0.002800109418, -0.0003001168104)),
    ('4-5 x, N', (-1.601593706, 0.1497896898, 2.311101942, -0.632161919)),
    ('4-5 y, N', (-5.100723098, -4.688156984, 0.1804493132, -5.363690872)),
    ('5-0 x, N', (0.0, 0.0, 0.0, 0.0)),
    ('5-0 y, N', (-10.0057231, -9.593156984, -4.724550687, -10.26869087)),
    ('5-0 normal, N', (-10.0057231, -9.593156984, -4.724550687, -10.26869087)),
    ('5-0 moment, N·m', (0.0, 0.0, 0.0, 0.0)),
    ('2-6 x, N', (-384.1109067, -144.0222997, -135.9972322, -59.36647921)),
    ('2-6 y, N', (288.2475905, -320.9112973, -307.2793431, 317.7651023)),
    ('6-7 x, N', (-690.6988102, 145.8669592, 143.7307238, -343.2096155)),
    ('6-7 y, N', (76.15216562, -106.8889463, -77.8133973, 70.48300737)),
    ('6-7 normal, N', (694.8841621, -180.8380951, -163.4424846, 350.3722228)),
    ('6-7 moment, N·m', (-0.005803498164, 0.003053504131, 0.0003700585278, 0.001010016472)),
    ('7-0 x, N', (-690.6988102, 145.8669592, 143.7307238, -343.2096155)),
    ('7-0 y, N', (71.24716562, -111.7939463, -82.7183973, 65.57800737)),
    ('6-8 x, N', (305.4405413, -290.1624366, -281.3570749, 285.1099508)),
    ('6-8 y, N', (207.5076999, -222.5690579, -240.1696431, 238.3134313)),
    ('8-9 x, N', (3.76141282, -1.204792884, 1.333270152, -1.841305541)),
    ('8-9 y, N', (-306.680805, 258.2102731, 238.8136332, -279.4795331)),
    ('9-0 x, N', (0.0, 0.0, 0.0, 0.0)),
    ('9-0 y, N', (-311.585805, 253.3052731, 233.9086332, -284.3845331)),
    ('9-0 normal, N', (311.585805, -253.3052731, -233.9086332, 284.3845331)),
    ('9-0 moment, N·m', (0.0, 0.0, 0.0, 0.0)),
    ('8-10 x, N', (297.0777964, -287.5487573, -283.9794671, 288.9475652)),
    ('8-10 y, N', (509.8817908, -487.7547413, -486.2386865, 511.257106)),
    ('10-11 x, N', (291.7985649, -285.9412561, -285.1829728, 291.0950012)),
    ('10-11 y, N', (505.40994, -495.2647835, -493.9513984, 504.1913319)),
    ('10-11 normal, N', (-583.5971298, 571.8825121, 570.3659456, -582.1900024)),
    ('10-11 moment, N·m', (-75.66401272, 49.38627007, 67.04152232, -70.35500948)),
    ('11-0 x, N', (291.7985649, -285.9412561, -285.1829728, 291.0950012)),
    ('11-0 y, N', (0.0, 0.0, 0.0, 0.0)),
    ('11-0 normal, N', (-291.7985649, 285.9412561, 285.1829728, -291.0950012)),
    ('11-0 moment, N·m', (-75.66401272, 49.38627007, 67.04152232, -70.35500948)),
)

CASES = {
    "a-slider-crank": ("slider_crank_press.yaml", VECTOR_A),
    "b-four-bar": ("four_bar_gravity.yaml", VECTOR_B),
    "c-course-11-link": ("course_11_link_forces.yaml", VECTOR_C),
}


def _computed(result, quantity: str) -> np.ndarray:
    """The value of one row of a vector table ("2-3 x, N", "6-7 moment, N·m", …)."""
    name = quantity.split(",")[0]
    if name == "driving torque":
        return result.driving
    pair, part = name.rsplit(" ", 1)
    return getattr(result.reactions[pair], part)


def _kind(quantity: str) -> str:
    if quantity.startswith("driving"):
        return "torque"
    return "moment" if " moment" in quantity else "force"


@pytest.mark.parametrize("case", list(CASES))
def test_vectors_are_reproduced(case: str) -> None:
    table, rows = CASES[case]
    model, data = load(table)
    result = kinetostatics(analyse(model, ANGLES, analogs=True), data, OMEGA)
    largest: dict[str, float] = {}
    for quantity, expected in rows:
        kind = _kind(quantity)
        largest[kind] = max(largest.get(kind, 0.0), float(np.max(np.abs(expected))))
    if not largest.get("moment"):  # couples that vanish: round-off beside the torque's scale
        largest["moment"] = largest["torque"]
    for quantity, expected in rows:
        tolerance = 1e-9 * largest[_kind(quantity)]
        np.testing.assert_allclose(_computed(result, quantity), expected, rtol=0,
                                   atol=tolerance, err_msg=f"{case}: {quantity}")
    assert set(result.reactions) == set(model.pair_links)


@pytest.mark.parametrize("case", list(CASES))
def test_checks_hold_over_the_cycle(case: str) -> None:
    """Power balance and every link's residual at 360 positions (``docs/forces.md`` §5)."""
    model, data = load(CASES[case][0])
    result = kinetostatics(analyse(model, points=360, analogs=True), data, OMEGA)
    assert np.all(result.reason == 0)
    assert np.all(np.abs(result.power_balance) <= 1e-10 * result.power_scale)
    for link, residual in result.residuals.items():
        assert np.max(residual.force) <= 1e-10, link
        assert np.max(residual.moment) <= 1e-10, link
