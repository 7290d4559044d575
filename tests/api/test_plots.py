"""The SVG plot endpoints: the documents parse as XML, hold the expected series with the computed values, label
their axes with units and carry the thesis's notation; the min-radius figure against Eqs. 9.2-9.3 by hand."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

BTRAIN = "table16-btrain"
SVG = "{http://www.w3.org/2000/svg}"
# Table 21, low bound (AASHTO 2003 / DNIT 2009): design speed [km/h] -> f
TABLE21_LOW = {30: 0.17, 40: 0.17, 50: 0.16, 60: 0.15, 70: 0.14, 80: 0.14, 90: 0.13, 100: 0.12, 110: 0.11, 120: 0.09}


def f_low(v):
    speeds = sorted(TABLE21_LOW)
    return np.interp(v, speeds, [TABLE21_LOW[s] for s in speeds])


class Plot:
    def __init__(self, response):
        assert response.status_code == 200, response.text
        assert response.headers["content-type"] == "image/svg+xml"
        self.root = ET.fromstring(response.content)
        assert self.root.tag == f"{SVG}svg"
        groups = list(self.root.iter(f"{SVG}g"))
        self.series = {}
        for g in groups:
            if g.get("class") == "series":
                line = g.find(f"{SVG}polyline")
                xs = [float(v) for v in line.get("data-x").split()]
                ys = [float(v) for v in line.get("data-y").split()]
                assert len(line.get("points").split()) == len(xs) == len(ys)
                self.series[g.get("data-name")] = (xs, ys)
        self.markers = [float(g.get("data-x")) for g in groups if g.get("class") == "marker"]
        self.texts = {t.get("class"): t.text for t in self.root.iter(f"{SVG}text") if t.get("class")}
        self.y_labels = [t.text for t in self.root.iter(f"{SVG}text") if t.get("class") == "y-label"]
        self.caption = " ".join(t.text for t in self.root.iter(f"{SVG}text") if t.get("class") == "caption")
        self.legend = [t.text for g in groups if g.get("class") == "legend-item" for t in g.iter(f"{SVG}text")]


def plot(client, name, body):
    return Plot(client.post(f"/v1/plots/{name}", json=body))


@pytest.fixture(scope="module")
def curves(shared_client):
    r = shared_client.post("/v1/srt", json={"vehicle": BTRAIN, "include_curves": True, "curve_points": 21})
    return r.json()


def approx6(values):
    return pytest.approx(values, rel=1e-5, abs=1e-9)  # data-x / data-y keep 6 significant digits


def test_tire_loads_figure_92(shared_client, curves):
    p = plot(shared_client, "tire-loads", {"vehicle": BTRAIN, "curve_points": 21})
    c = curves["curves"]
    assert list(p.series) == ["Fz1 front outer", "Fz3 front inner", "Fz17 rear outer", "Fz19 rear inner"]
    for name, key in [("Fz1 front outer", "fz_front_outer_kn"), ("Fz3 front inner", "fz_front_inner_kn"),
                      ("Fz17 rear outer", "fz_rear_outer_kn"), ("Fz19 rear inner", "fz_rear_inner_kn")]:  # fmt: skip
        xs, ys = p.series[name]
        assert len(xs) == 21 and xs == approx6(c["ay_g"]) and ys == approx6(c[key])
    assert p.legend == list(p.series)
    # markers at SRT_ts and SRT_3D (3d, full stage)
    sv = curves["stage_values"]
    assert p.markers == approx6([sv["srt_ts"], sv["srt_3d"]])
    assert p.texts["x-label"] == "lateral acceleration ay/g [-]" and p.y_labels == ["normal load Fz [kN]"]
    assert "Fz1, Fz3: front outer/inner" in p.caption and "SRT_ts, SRT_3D" in p.caption
    assert "Figs. 85-87, 92" in p.caption
    assert p.root.find(f"{SVG}title").text == "Tire normal loads against ay/g: table16-btrain"


def test_llt_figure_93(shared_client, curves):
    p = plot(shared_client, "llt", {"vehicle": BTRAIN, "curve_points": 21})
    assert list(p.series) == ["LLTf front", "LLTr rear"]
    assert p.series["LLTr rear"][1] == approx6(curves["curves"]["llt_rear"])
    assert p.series["LLTr rear"][1][-1] == pytest.approx(1.0, abs=1e-5)  # lift-off: LLTr = 1 at the SRT
    assert p.series["LLTf front"][1][-1] == pytest.approx(0.7, abs=1e-3)  # LLTf/LLTr = 0.7 (Kamnik)
    assert p.y_labels == ["lateral load transfer LLT [-]"] and "Fig. 93" in p.caption


def test_roll_figure_94(shared_client, curves):
    p = plot(shared_client, "roll", {"vehicle": BTRAIN, "curve_points": 21})
    assert list(p.series) == ["theta_3D"]
    assert p.series["theta_3D"][1] == approx6(curves["curves"]["roll_angle_deg"])
    assert p.y_labels == ["roll angle theta [deg]"] and "Fig. 94" in p.caption


def test_cg_path_figures_96_97_in_two_panels(shared_client, curves):
    p = plot(shared_client, "cg-path", {"vehicle": BTRAIN, "curve_points": 21})
    assert list(p.series) == ["h1", "h2"]
    assert len([g for g in p.root.iter(f"{SVG}g") if g.get("class") == "panel"]) == 2
    assert p.series["h1"][1] == approx6(curves["curves"]["cg_lateral_m"])
    assert p.series["h2"][1] == approx6(curves["curves"]["cg_height_m"])
    assert p.series["h1"][1][0] == pytest.approx(0.93)  # at rest, the half track (Table 16)
    assert p.y_labels == ["h1, lateral CG position [m]", "h2, CG height [m]"] and "Figs. 96-97" in p.caption


def test_2d_has_only_the_rear_series(shared_client):
    body = {"vehicle": "table14-semitrailer", "model": "2d", "curve_points": 11}
    tires = plot(shared_client, "tire-loads", body)
    assert list(tires.series) == ["Fz17 rear outer", "Fz19 rear inner"]
    assert all(len(xs) == 11 for xs, _ in tires.series.values())
    srt = shared_client.post("/v1/srt", json={"vehicle": "table14-semitrailer", "model": "2d"}).json()["srt"]
    assert tires.markers == approx6([srt])
    assert list(plot(shared_client, "llt", body).series) == ["LLTr rear"]
    assert list(plot(shared_client, "roll", body).series) == ["theta_2D"]


def test_the_plots_share_the_cached_solve_and_are_cached(client):
    body = {"vehicle": BTRAIN, "curve_points": 11}
    first = client.post("/v1/plots/roll", json=body)
    assert first.headers["x-cache"] == "miss"
    again = client.post("/v1/plots/roll", json=body)
    assert again.headers["x-cache"] == "hit" and again.content == first.content
    assert again.headers["etag"] == first.headers["etag"]
    # the other figures of the case and /v1/srt with the same curves reuse the engine's result: no new solve
    solves = _srt_solves()
    assert client.post("/v1/plots/llt", json=body).headers["x-cache"] == "miss"
    srt = client.post("/v1/srt", json={**body, "include_curves": True})
    assert srt.status_code == 200 and len(srt.json()["curves"]["ay_g"]) == 11
    assert _srt_solves() == solves


def _srt_solves() -> float:
    from prometheus_client import REGISTRY

    return sum(
        s.value
        for m in REGISTRY.collect()
        if m.name == "rollover_solve_seconds"
        for s in m.samples
        if s.name.endswith("_count") and s.labels.get("operation") == "srt"
    )


def test_closed_forms_have_no_curves_to_plot(shared_client):
    r = shared_client.post("/v1/plots/tire-loads", json={"vehicle": BTRAIN, "model": "rill"})
    assert r.status_code == 422 and r.json()["errors"][0]["field"] == "model"


# ------------------------------------------------------------------------------------ min radius

HIGH_LOAD = {"vehicle": BTRAIN, "rear_llt_limit": 0.6, "load": {"vertical_offset_m": 0.5}}


def test_min_radius_figure_against_eqs_9_2_and_9_3(shared_client):
    # the thesis's figures use Table 21 (low bound) over its 30-120 km/h
    body = {**HIGH_LOAD, "superelevation_percent": 4.0, "slope_percent": -2.0, "points": 10}
    p = plot(shared_client, "min-radius", {**body, "design_standard": "thesis-table21"})
    assert list(p.series) == ["Eq. 9.2 (side friction)", "Eq. 9.3 (rollover)"]
    srt = shared_client.post(
        "/v1/srt", json={**HIGH_LOAD, "road": {"bank_percent": 4.0, "slope_percent": -2.0}}
    ).json()["srt"]
    v = np.linspace(30, 120, 10)
    xs, r92 = p.series["Eq. 9.2 (side friction)"]
    assert xs == approx6(list(v))
    assert r92 == approx6(list(v**2 / (127 * (0.04 + f_low(v)))))  # Eq. 9.2 with Table 21
    assert p.series["Eq. 9.3 (rollover)"][1] == approx6(list(v**2 / (127 * srt)))  # Eq. 9.3
    assert p.texts["x-label"] == "design speed V [km/h]" and p.y_labels == ["minimum radius Rmin [m]"]
    assert "Figs. 108-114" in p.caption and f"SRT = {srt:.3f} g" in p.caption
    # the marker where they cross: 0.01 e + f(V) = SRT (rollover governs below it: f falls with V)
    (cross,) = p.markers
    assert 30 < cross < 120
    assert 0.04 + f_low(cross) == pytest.approx(srt, abs=1e-6)
    label = [t.text for g in p.root.iter(f"{SVG}g") if g.get("class") == "marker" for t in g.iter(f"{SVG}text")]
    assert label[0].startswith("Eq. 9.3 governs below")


def test_min_radius_without_a_crossing_has_no_marker(shared_client):
    # the B-train on 8 % with LLT 1: SRT ~0.41 > 0.08 + f (Table 21 low: at most 0.17) for every speed -> side
    # friction governs throughout
    body = {"vehicle": BTRAIN, "superelevation_percent": 8.0, "design_standard": "thesis-table21"}
    p = plot(shared_client, "min-radius", body)
    _, r92 = p.series["Eq. 9.2 (side friction)"]
    _, r93 = p.series["Eq. 9.3 (rollover)"]
    assert all(a > b for a, b in zip(r92, r93, strict=True)) and p.markers == []
    assert len(r92) == 19  # 30-120 km/h every 5 km/h


def test_min_radius_figure_of_the_default_standard(shared_client):
    # AASHTO 2018 (the default) covers 20-120 km/h: 21 speeds every 5 km/h, f = Table 3-7's f_max; at 20 km/h
    # f_max = 0.35, so 0.08 + f = 0.43 exceeds the B-train's SRT on 8 % (~0.41): rollover governs the slowest
    # speeds and the curves cross where 0.08 + f(V) = SRT
    p = plot(shared_client, "min-radius", {"vehicle": BTRAIN, "superelevation_percent": 8.0})
    v, r92 = p.series["Eq. 9.2 (side friction)"]
    assert v == approx6(list(np.arange(20.0, 121.0, 5.0)))
    f_aashto = np.interp(v, [20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120],
                         [0.35, 0.28, 0.23, 0.19, 0.17, 0.15, 0.14, 0.13, 0.12, 0.11, 0.09])  # fmt: skip
    assert r92 == approx6(list(np.asarray(v) ** 2 / (127 * (0.08 + f_aashto))))
    srt = shared_client.post("/v1/srt", json={"vehicle": BTRAIN, "road": {"bank_percent": 8.0}}).json()["srt"]
    (cross,) = p.markers
    assert 0.08 + np.interp(cross, [20, 30], [0.35, 0.28]) == pytest.approx(srt, abs=1e-6)
    assert "AASHTO" in p.caption and "Table 3-7" in p.caption
    # a speed outside the standard's range is refused, naming the range
    body = {"vehicle": BTRAIN, "superelevation_percent": 8.0, "design_standard": "dnit-1999", "speed_min_kmh": 20}
    r = shared_client.post("/v1/plots/min-radius", json=body)
    assert r.status_code == 422 and "30-120 km/h" in r.json()["detail"]


@pytest.mark.parametrize(
    ("body", "field"),
    [
        ({"superelevation_percent": 8.0, "speed_min_kmh": 80.0, "speed_max_kmh": 60.0}, "speed_max_kmh"),
        ({"superelevation_percent": 8.0, "speed_max_kmh": 140.0}, "speed_max_kmh"),
        ({"superelevation_percent": -20.0}, "superelevation_percent"),
        ({"superelevation_percent": 8.0, "points": 1}, "points"),
        ({}, "superelevation_percent"),
    ],
)
def test_min_radius_errors_name_the_field(shared_client, body, field):
    r = shared_client.post("/v1/plots/min-radius", json={"vehicle": BTRAIN, **body})
    assert r.status_code == 422 and r.headers["content-type"] == "application/problem+json"
    assert field in [e["field"] for e in r.json()["errors"]]


def test_min_radius_takes_any_model(shared_client):
    # Eq. 9.3 needs only the SRT: the banked rigid closed form (Eq. 2.8) is t/2h + e
    p = plot(shared_client, "min-radius", {"vehicle": BTRAIN, "model": "rigid-bank", "superelevation_percent": 6.0,
                                           "points": 2, "speed_min_kmh": 30})  # fmt: skip
    srt = 0.93 / 2.06 + 0.06
    assert p.series["Eq. 9.3 (rollover)"][1] == approx6([30**2 / (127 * srt), 120**2 / (127 * srt)])
    assert math.isclose(p.series["Eq. 9.3 (rollover)"][0][1], 120)


def test_a_flat_case_still_draws(shared_client):
    # a rear LLT limit of 1e-15 ends the ramp at rest: ay spans 1e-16 and the roll is a constant round-off
    # (-2.5e-14 deg); the axes must still span a drawable range
    p = plot(shared_client, "roll", {"vehicle": BTRAIN, "rear_llt_limit": 1e-15, "curve_points": 3})
    xs, ys = p.series["theta_3D"]
    assert len(xs) == 3 and max(xs) < 1e-12 and max(abs(y) for y in ys) < 1e-12
