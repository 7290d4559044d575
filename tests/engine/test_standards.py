"""Design standards (engine/standards.py) against their published tables and the methods' invariants.

Sources of the expected numbers (each typed in here from the source, independently of the engine's tables):
* AASHTO Green Book 2018, Table 3-7 (metric) f_max: transcription in Romyull-Islam/civil-ai
  src/lib/eng/roadgeo.ts; second listing "AASHTO 2011" (side-friction compilation, academia-assets 98179549,
  row a) at 20/40/60/80/100/120 km/h; the brief's 0.19/0.17/0.15 at 50/60/70 km/h.
* AASHTO rounded R_min and superelevation cells: NYSDOT HDM Ch. 2 metric Exhibits M2-13 (e_max 6 %) and M2-14
  (e_max 8 %), as transcribed in Romyull-Islam/civil-ai tests/roadgeo.test.ts.
* DNIT IPR-706 (1999) Quadros 5.4.3.1 and 5.4.3.2: DNIT crib-sheet transcription (public code index file
  68642008325); worked case H-01 of TheVoidDweller/road-geometric-design-tool (80 km/h, R 1000 m, e_max 8 %).
* Thesis Table 21 (low and high bounds).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine import road as st
from engine.errors import InvalidRoad
from engine.road.min_radius import meets_min_radius

# --------------------------------------------------------------------------------- published tables

# AASHTO 2018 Table 3-7 (metric): design speed [km/h] -> f_max
AASHTO_TABLE_3_7_F = {20: 0.35, 30: 0.28, 40: 0.23, 50: 0.19, 60: 0.17, 70: 0.15, 80: 0.14, 90: 0.13, 100: 0.12,
                      110: 0.11, 120: 0.09}  # fmt: skip
# second, independent listing of the same factors ("AASHTO 2011", row a) and the brief's Green Book values
AASHTO_2011_LISTING_F = {20: 0.35, 40: 0.23, 60: 0.17, 80: 0.14, 100: 0.12, 120: 0.09}
BRIEF_GREEN_BOOK_F = {50: 0.19, 60: 0.17, 70: 0.15}

# NYSDOT Exhibit M2-14 (e_max 8 %) and M2-13 (e_max 6 %), the e = e_max row: design speed -> rounded R_min [m]
NYSDOT_M2_14_RMIN = {20: 7, 30: 20, 40: 41, 50: 73, 60: 113, 70: 168, 80: 229, 90: 304, 100: 394, 110: 501, 120: 667}
NYSDOT_M2_13_RMIN = {20: 8, 120: 756}
# NYSDOT Exhibit M2-14 (e_max 8 %), rows e = 3.0 % and 6.0 %: design speed -> R [m]
NYSDOT_M2_14_ROWS = {
    3.0: {20: 81, 30: 199, 40: 354, 50: 496, 60: 684, 70: 916, 80: 1150, 90: 1410, 100: 1730, 110: 2000, 120: 2370},
    6.0: {20: 19, 30: 55, 40: 106, 50: 172, 60: 253, 70: 360, 80: 469, 90: 595, 100: 746, 110: 894, 120: 1100},
}

# Green Book average running speeds for Method 5 (civil-ai roadgeo.ts AASHTO_RUNNING_SPEED): design -> running
RUNNING_SPEED = {20: 20, 30: 30, 40: 40, 50: 47, 60: 55, 70: 63, 80: 70, 90: 77, 100: 85, 110: 91, 120: 98}

# DNIT IPR-706 Quadro 5.4.3.1: design speed -> f_max
DNIT_QUADRO_5_4_3_1 = {30: 0.19, 40: 0.18, 50: 0.16, 60: 0.15, 70: 0.15, 80: 0.14, 90: 0.14, 100: 0.13, 110: 0.12,
                       120: 0.11}  # fmt: skip
# DNIT IPR-706 Quadro 5.4.3.2: e_max [%] -> R_min [m] at 30, 40, ..., 120 km/h
DNIT_QUADRO_5_4_3_2 = {
    4: (30, 55, 100, 150, 205, 280, 355, 465, 595, 755),
    6: (30, 50, 90, 135, 185, 250, 320, 415, 530, 665),
    8: (25, 50, 80, 125, 170, 230, 290, 375, 475, 595),
    10: (25, 45, 75, 115, 155, 210, 265, 340, 435, 540),
    12: (25, 40, 70, 105, 145, 195, 245, 315, 395, 495),
}
DNIT_SPEEDS = (30, 40, 50, 60, 70, 80, 90, 100, 110, 120)

# Thesis Table 21: design speed -> (low, high)
TABLE21 = {30: (0.17, 0.28), 40: (0.17, 0.23), 50: (0.16, 0.19), 60: (0.15, 0.17), 70: (0.14, 0.15), 80: (0.14, 0.14),
           90: (0.13, 0.14), 100: (0.12, 0.13), 110: (0.11, 0.12), 120: (0.09, 0.11)}  # fmt: skip


def eq_9_2(v, e_percent, f):
    """Thesis Eq. 9.2 written out here (not the engine's function)."""
    return v**2 / (127.0 * (0.01 * e_percent + f))


# ------------------------------------------------------------------------------------------ look-up


def test_known_ids_and_their_citations():
    assert set(st.STANDARDS) == {"aashto-2018", "dnit-1999", "thesis-table21"}
    a, d, t = (st.get_standard(i) for i in ("aashto-2018", "dnit-1999", "thesis-table21"))
    assert "7th ed." in a.citation and "2018" in a.citation and "Table 3-7" in a.citation
    assert "IPR-706" in d.citation and "1999" in d.citation and "Quadro 5.4.3.2" in d.citation
    assert t.table == "Table 21" and t.bound == "low"
    assert a.speed_range_kmh == (20.0, 120.0) and d.speed_range_kmh == (30.0, 120.0)
    assert t.speed_range_kmh == (30.0, 120.0)
    assert st.get_standard("thesis-table21", "high").bound == "high"


def test_unknown_id_is_refused_with_the_known_ids():
    with pytest.raises(InvalidRoad) as exc:
        st.get_standard("aashto-2011")
    assert exc.value.field == "design_standard" and exc.value.value == "aashto-2011"
    for known in st.STANDARDS:
        assert known in str(exc.value)


def test_a_bound_only_applies_to_table21():
    with pytest.raises(InvalidRoad) as exc:
        st.side_friction_factor("aashto-2018", 60.0, bound="high")
    assert exc.value.field == "side_friction_bound"
    with pytest.raises(InvalidRoad) as exc:
        st.get_standard("thesis-table21", "median")
    assert exc.value.field == "side_friction_bound"


# ------------------------------------------------------------------------------------ side friction


@pytest.mark.parametrize("speed,f", sorted(AASHTO_TABLE_3_7_F.items()), ids=lambda x: str(x))
def test_aashto_table_3_7_f_max(speed, f):
    # Green Book 2018 Table 3-7 (metric), cell "maximum f" at this design speed
    assert st.side_friction_factor("aashto-2018", speed) == f


@pytest.mark.parametrize("speed,f", sorted({**AASHTO_2011_LISTING_F, **BRIEF_GREEN_BOOK_F}.items()), ids=str)
def test_aashto_f_max_agrees_with_the_second_listing(speed, f):
    # cross-check: "AASHTO 2011" row a of the side-friction compilation; brief: 0.19/0.17/0.15 at 50/60/70 km/h
    assert st.side_friction_factor("aashto-2018", speed) == f


@pytest.mark.parametrize("speed,f", sorted(DNIT_QUADRO_5_4_3_1.items()), ids=str)
def test_dnit_quadro_5_4_3_1_f_max(speed, f):
    # IPR-706 Quadro 5.4.3.1, cell at this design speed
    assert st.side_friction_factor("dnit-1999", speed) == f


def test_dnit_f_max_cross_check_at_80_kmh():
    # TheVoidDweller/road-geometric-design-tool, case H-01: "side friction f = 0.14" at 80 km/h (IPR 706)
    assert st.side_friction_factor("dnit-1999", 80.0) == 0.14


@pytest.mark.parametrize("speed", sorted(TABLE21))
def test_table21_bounds(speed):
    lo, hi = TABLE21[speed]  # thesis Table 21 row
    assert st.side_friction_factor("thesis-table21", speed) == lo
    assert st.side_friction_factor("thesis-table21", speed, bound="high") == hi
    assert st.side_friction_factor("thesis-table21", speed, bound="mid") == pytest.approx(0.5 * (lo + hi), abs=1e-15)


def test_linear_between_rows_and_vectorised():
    assert st.side_friction_factor("aashto-2018", 55.0) == pytest.approx(0.5 * (0.19 + 0.17), abs=1e-15)
    assert st.side_friction_factor("dnit-1999", 35.0) == pytest.approx(0.5 * (0.19 + 0.18), abs=1e-15)
    out = st.side_friction_factor("dnit-1999", np.array([[30.0, 120.0], [45.0, 80.0]]))
    assert out.shape == (2, 2) and out == pytest.approx(np.array([[0.19, 0.11], [0.17, 0.14]]), abs=1e-15)


OUT_OF_RANGE = [("aashto-2018", 130.0, "20-120"), ("aashto-2018", 15.0, "20-120"), ("dnit-1999", 25.0, "30-120"),
                ("thesis-table21", 125.0, "30-120")]  # fmt: skip


@pytest.mark.parametrize("standard,bad,rng", OUT_OF_RANGE)
def test_speed_outside_the_range_names_the_range_and_the_standard(standard, bad, rng):
    with pytest.raises(InvalidRoad) as exc:
        st.side_friction_factor(standard, np.array([60.0, bad]))
    assert exc.value.field == "design_speed_kmh" and exc.value.value == bad
    assert rng in str(exc.value) and standard in str(exc.value)
    with pytest.raises(InvalidRoad, match=rng):
        st.side_friction_factor(standard, math.nan)


# ----------------------------------------------------------------------------------- minimum radius


@pytest.mark.parametrize("e_max", sorted(DNIT_QUADRO_5_4_3_2))
@pytest.mark.parametrize("i", range(len(DNIT_SPEEDS)), ids=lambda i: f"{DNIT_SPEEDS[i]}kmh")
def test_dnit_quadro_5_4_3_2_r_min(e_max, i):
    speed, published = DNIT_SPEEDS[i], DNIT_QUADRO_5_4_3_2[e_max][i]  # Quadro 5.4.3.2, row e_max, column speed
    r = st.min_radius_m("dnit-1999", speed, e_max)
    assert r.source == "table" and r.radius_m == published
    # the published cell is Eq. 9.2 with the Quadro 5.4.3.1 f_max, rounded to the nearest 5 m
    assert 5 * round(eq_9_2(speed, e_max, DNIT_QUADRO_5_4_3_1[speed]) / 5) == published
    formula = st.min_radius_m("dnit-1999", speed, e_max, tabulated=False)
    assert formula.source == "formula" and formula.radius_m == pytest.approx(
        eq_9_2(speed, e_max, DNIT_QUADRO_5_4_3_1[speed]), rel=1e-12
    )


def test_dnit_r_min_cross_check_at_80_kmh():
    # case H-01: "80^2 / [127 (0.08 + 0.14)] = 229.06 m"; adopted "IPR 706 Quadro 5.4.3.2: 230 m"
    r = st.min_radius_m("dnit-1999", 80.0, 8.0)
    assert r.radius_m == 230 and r.formula_radius_m == pytest.approx(229.06, abs=0.005)


@pytest.mark.parametrize(
    "e_max,speed,published",
    [(8.0, v, r) for v, r in sorted(NYSDOT_M2_14_RMIN.items())]
    + [(6.0, v, r) for v, r in sorted(NYSDOT_M2_13_RMIN.items())],
)
def test_aashto_rounded_r_min(e_max, speed, published):
    # NYSDOT Exhibit M2-14 (e_max 8 %) / M2-13 (e_max 6 %), row e = e_max, column speed
    r = st.min_radius_m("aashto-2018", speed, e_max)
    assert r.source == "table" and r.radius_m == published
    # the published radius is Eq. 9.2 with Table 3-7's f_max rounded to the nearest metre
    assert round(eq_9_2(speed, e_max, AASHTO_TABLE_3_7_F[speed])) == published


def test_untabulated_cells_fall_back_to_eq_9_2():
    r = st.min_radius_m("aashto-2018", 80.0, 4.0)  # no transcription of Table 3-7's e_max 4 % column was found
    assert r.source == "formula" and r.radius_m == pytest.approx(6400 / (127 * 0.18), rel=1e-12) and r.f_max == 0.14
    between = st.min_radius_m("dnit-1999", 85.0, 8.0)  # between rows: f interpolated (0.14 at 80 and 90 km/h)
    assert between.source == "formula" and between.radius_m == pytest.approx(85**2 / (127 * 0.22), rel=1e-12)
    t21 = st.min_radius_m("thesis-table21", 60.0, 0.0)  # Table 21 has no radius table; e = 0 is allowed by Eq. 9.2
    assert t21.source == "formula" and t21.radius_m == pytest.approx(3600 / (127 * 0.15), rel=1e-12)


def test_min_radius_refuses_a_bad_e_max():
    for bad in (-1.0, 12.5, math.inf):
        with pytest.raises(InvalidRoad) as exc:
            st.min_radius_m("dnit-1999", 60.0, bad)
        assert exc.value.field == "max_superelevation_percent" and "[0, 12]" in str(exc.value)


def test_meets_min_radius_uses_the_published_value_at_a_row_and_eq_9_2_between_rows():
    # 80 km/h, e_max 8 %: Quadro 5.4.3.2 gives 230 m although Eq. 9.2 gives 229.06 m
    assert meets_min_radius("dnit-1999", 80.0, 230.0, 8.0).meets
    short = meets_min_radius("dnit-1999", 80.0, 229.5, 8.0)
    assert not short.meets and short.min_radius_m == 230 and short.source == "table"
    assert short.margin_m == pytest.approx(-0.5)
    mid = meets_min_radius("dnit-1999", 85.0, 259.0, 8.0)
    assert mid.source == "formula" and mid.min_radius_m == pytest.approx(85**2 / (127 * 0.22)) and mid.meets
    with pytest.raises(InvalidRoad) as exc:
        meets_min_radius("aashto-2018", 130.0, 500.0, 8.0)
    assert exc.value.field == "posted_speed_kmh" and "20-120" in str(exc.value)


# ----------------------------------------------------------------------------------- superelevation

SPEEDS = {"aashto-2018": (20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120), "dnit-1999": DNIT_SPEEDS}
CASES = [(s, v, e) for s, vs in SPEEDS.items() for v in vs for e in (4.0, 6.0, 8.0, 10.0, 12.0)]


@pytest.mark.parametrize("standard,speed,e_max", CASES)
def test_distribution_invariants(standard, speed, e_max):
    f_max = st.side_friction_factor(standard, speed)
    r_min = eq_9_2(speed, e_max, f_max)
    at_min = st.superelevation_percent(standard, speed, r_min, e_max)
    assert at_min.superelevation_percent == pytest.approx(e_max, abs=1e-9)  # e_max at R_min
    assert at_min.side_friction == pytest.approx(f_max, abs=1e-11) and at_min.min_radius_m == pytest.approx(r_min)
    radii = r_min * np.geomspace(1.0, 1e3, 400)
    t = st.superelevation_table(standard, speed, e_max, radii)
    assert np.all(np.diff(t.superelevation_percent) <= 1e-12)  # non-increasing in R
    # far out (R = 1000 R_min) e tends to 0 along the method's asymptote: DNIT e ~ 2 e_max R_min/R (first-order
    # term of the formula); Method 5 e ~ V_R^2/(127 R) (the first leg's slope leaves what the running speed needs)
    far = 100 * RUNNING_SPEED[speed] ** 2 / (127 * radii[-1]) if standard == "aashto-2018" else 2e-3 * e_max
    assert t.superelevation_percent[-1] == pytest.approx(far, rel=1e-2)
    assert np.all(t.superelevation_percent >= 0)
    demand = speed**2 / (127.0 * radii)
    assert t.superelevation_percent / 100 + t.side_friction == pytest.approx(demand, rel=1e-12)  # e + f = V^2/(127R)
    assert np.all(t.side_friction <= f_max + 1e-12)  # f <= f_max


def test_dnit_formula_worked_case_h01():
    # case H-01: "8 x [2 (229.06/1,000) - (229.06/1,000)^2] = 3.25 %, rounded up to 0.1 %: 3.3 %"
    r = st.superelevation_percent("dnit-1999", 80.0, 1000.0, 8.0)
    assert round(r.superelevation_percent, 2) == 3.25 and math.ceil(10 * r.superelevation_percent) / 10 == 3.3
    assert r.method.startswith("DNER/DNIT IPR-706")


# NYSDOT M2-14 rows e = 3.0 % and 6.0 % (e_max 8 %). The table lists R for e in 0.2 % steps, so a cell is
# reproduced when Method 5 gives e at the printed radius within half a step (0.1 %) of the row's e. At 20 and
# 30 km/h three printed radii differ from Method 5 with the transcribed running speeds by 0.12-0.14 %:
# not reproduced, kept as strict xfails so that a change in the method or the data shows up.
NOT_REPRODUCED = {(3.0, 20), (6.0, 20), (6.0, 30)}
AASHTO_CELLS = [
    pytest.param(
        e, v, r,
        marks=[pytest.mark.xfail(strict=True, reason="low-speed cell off Method 5 by > 0.1 %")]
        if (e, v) in NOT_REPRODUCED else [],
        id=f"e{e:g}-{v}kmh-R{r}",
    )
    for e, row in NYSDOT_M2_14_ROWS.items()
    for v, r in sorted(row.items())
]  # fmt: skip


@pytest.mark.parametrize("e_row,speed,radius", AASHTO_CELLS)
def test_aashto_method5_reproduces_nysdot_m2_14(e_row, speed, radius):
    # NYSDOT Exhibit M2-14 (Green Book metric superelevation table, e_max 8 %): row e_row, column speed
    e = st.superelevation_percent("aashto-2018", speed, radius, 8.0).superelevation_percent
    assert abs(e - e_row) <= 0.1


def test_method5_at_the_pi_is_h_plus_the_middle_ordinate():
    # Green Book Method 5 at 80 km/h, e_max 8 %, f_max 0.14, V_R 70 km/h, written out here:
    # 1/R_PI = e_max / (V_R^2/127), 1/R_min = (e_max + f_max) / (V_D^2/127), h = e_max (V_D^2/V_R^2 - 1),
    # tan a1 = h R_PI, tan a2 = (f_max - h) / (1/R_min - 1/R_PI), M_O = (1/R_PI)(1/R_min - 1/R_PI)(tan a2 - tan a1)
    # / (2/R_min); at the PI both legs give f = h + M_O
    x_pi, x_min = 0.08 * 127 / 70.0**2, 0.22 * 127 / 80.0**2
    h = 0.08 * (80.0**2 / 70.0**2 - 1)
    tan1, tan2 = h / x_pi, (0.14 - h) / (x_min - x_pi)
    m_o = x_pi * (x_min - x_pi) * (tan2 - tan1) / (2 * x_min)
    out = st.superelevation_percent("aashto-2018", 80.0, 1 / x_pi, 8.0)
    assert out.side_friction == pytest.approx(h + m_o, rel=1e-12)
    assert out.superelevation_percent == pytest.approx(100 * (80.0**2 * x_pi / 127 - h - m_o), rel=1e-12)


def test_radius_below_r_min_is_refused_and_names_r_min():
    with pytest.raises(InvalidRoad) as exc:
        st.superelevation_percent("aashto-2018", 80.0, 200.0, 8.0)
    assert exc.value.field == "radius_m" and exc.value.value == 200.0
    assert "R_min = 229.1 m" in str(exc.value)
    with pytest.raises(InvalidRoad, match=r"R_min = 229\.1 m"):
        st.superelevation_table("dnit-1999", 80.0, 8.0, [500.0, 100.0])


def test_table21_has_no_distribution_of_its_own():
    with pytest.raises(InvalidRoad) as exc:
        st.superelevation_percent("thesis-table21", 80.0, 500.0, 8.0)
    assert exc.value.field == "design_standard"
    assert "aashto-2018" in str(exc.value) and "dnit-1999" in str(exc.value)


def test_superelevation_refuses_bad_inputs():
    with pytest.raises(InvalidRoad) as exc:
        st.superelevation_percent("dnit-1999", 80.0, 500.0, 0.0)
    assert exc.value.field == "max_superelevation_percent"
    with pytest.raises(InvalidRoad) as exc:
        st.superelevation_percent("dnit-1999", 80.0, -5.0, 8.0)
    assert exc.value.field == "radius_m"
    with pytest.raises(InvalidRoad) as exc:
        st.superelevation_percent("dnit-1999", 20.0, 500.0, 8.0)
    assert exc.value.field == "design_speed_kmh" and "30-120" in str(exc.value)


# ------------------------------------------------------------------------------ side-friction speed


@pytest.mark.parametrize("standard", ["aashto-2018", "dnit-1999", "thesis-table21"])
def test_side_friction_speed_solves_the_implicit_equation(standard):
    r = np.array([60.0, 250.0, 500.0])
    e = np.array([8.0, 6.0, 2.0])
    out = st.side_friction_speed(standard, r, e)
    f = st.side_friction_factor(standard, out.speed_kmh)
    assert out.speed_kmh == pytest.approx(np.sqrt(127 * r * (0.01 * e + f)), rel=1e-12)
    assert not out.clamped.any() and out.side_friction == pytest.approx(f, abs=1e-15)
    # a curve at the standard's own R_min for e_max is used up exactly at the design speed
    v = st.side_friction_speed_kmh(standard, st.min_radius_m(standard, 70.0, 8.0, tabulated=False).radius_m, 8.0)
    assert v == pytest.approx(70.0, rel=1e-12)


def test_side_friction_speed_clamps_and_says_so():
    out = st.side_friction_speed("dnit-1999", [10.0, 20000.0], [0.0, 2.0])
    assert out.below_range.tolist() == [True, False] and out.above_range.tolist() == [False, True]
    assert out.speed_kmh[0] == pytest.approx(math.sqrt(127 * 10 * 0.19))  # f(30 km/h) used below the range
    assert out.speed_kmh[1] == pytest.approx(math.sqrt(127 * 20000 * (0.02 + 0.11)))  # f(120 km/h) above it


def test_side_friction_speed_of_a_scalar_is_a_float():
    assert isinstance(st.side_friction_speed_kmh("thesis-table21", 250.0, 6.0), float)
