"""SRT targets and the tilt-table angle on every SRT result (issue 4, item 2), through HTTP.

Independent numbers: the rigid B-train's SRT is t/2h = 0.93 / 2.06 = 0.4515 g (Eq. 2.6, Table 16); the targets
are PBS / New Zealand's 0.35 g (general) and 0.40 g (dangerous goods); margin = SRT - target,
meets = SRT >= target, tilt-table angle = atan(SRT) in degrees.
"""

from __future__ import annotations

import math

import pytest

from app.settings import Settings

from .conftest import make_client

BTRAIN = "table16-btrain"
RIGID_SRT = 0.93 / 2.06  # Eq. 2.6 with Table 16


def post(client, path, body, status=200):
    r = client.post(path, json=body)
    assert r.status_code == status, r.text
    return r


def check_consistent(out: dict) -> None:
    """The invariants of every SRT result: the tilt angle of its own SRT, the targets judged on its level-road SRT
    (the same as ``srt`` on a level road)."""
    srt, level = out["srt"], out["level_road_srt"]
    assert out["tilt_table_angle_deg"] == pytest.approx(math.degrees(math.atan(srt)), rel=1e-12)
    for t in out["targets"]:
        assert t["judged_on"] == "level_road_srt"
        assert t["margin_g"] == pytest.approx(level - t["target_g"], abs=1e-15)
        assert t["meets"] == (level >= t["target_g"])


def test_default_targets_on_the_rigid_btrain(shared_client):
    out = post(shared_client, "/v1/srt", {"vehicle": BTRAIN, "model": "rigid"}).json()
    assert out["srt"] == pytest.approx(RIGID_SRT, rel=1e-12)
    assert [(t["name"], t["target_g"], t["meets"]) for t in out["targets"]] == [
        ("general", 0.35, True),
        ("dangerous_goods", 0.40, True),
    ]
    assert out["targets"][0]["margin_g"] == pytest.approx(RIGID_SRT - 0.35, rel=1e-12)
    assert out["targets"][1]["margin_g"] == pytest.approx(RIGID_SRT - 0.40, rel=1e-12)
    # atan(0.4515) = 24.30 deg
    assert out["tilt_table_angle_deg"] == pytest.approx(24.30, abs=0.01)
    check_consistent(out)


def test_the_3d_btrain_misses_both_default_targets(shared_client):
    # Ch. 9: 0.3364 g for the B-train (the engine: 0.339) is below PBS's 0.35 g
    out = post(shared_client, "/v1/srt", {"vehicle": BTRAIN}).json()
    assert out["srt"] < 0.35
    assert [t["meets"] for t in out["targets"]] == [False, False]
    assert all(t["margin_g"] < 0 for t in out["targets"])
    check_consistent(out)


def test_request_targets_replace_the_defaults_in_increasing_order(shared_client):
    body = {"vehicle": BTRAIN, "model": "rigid", "targets": {"tanker_fleet": 0.5, "low": 0.2, "exact": RIGID_SRT}}
    out = post(shared_client, "/v1/srt", body).json()
    assert [t["name"] for t in out["targets"]] == ["low", "exact", "tanker_fleet"]
    exact = out["targets"][1]
    # a target equal to the SRT is met with a zero margin (meets means SRT >= target)
    assert out["srt"] == RIGID_SRT and exact["meets"] is True and exact["margin_g"] == 0.0
    assert out["targets"][2]["meets"] is False
    check_consistent(out)


def test_targets_are_in_the_cache_key_but_their_order_is_not(client):
    a = post(client, "/v1/srt", {"vehicle": BTRAIN, "model": "rigid", "targets": {"a": 0.3, "b": 0.5}})
    b = post(client, "/v1/srt", {"vehicle": BTRAIN, "model": "rigid", "targets": {"b": 0.5, "a": 0.3}})
    assert b.headers["x-cache"] == "hit" and b.headers["etag"] == a.headers["etag"] and b.content == a.content
    c = post(client, "/v1/srt", {"vehicle": BTRAIN, "model": "rigid", "targets": {"a": 0.3, "b": 0.51}})
    assert c.headers["x-cache"] == "miss" and c.headers["etag"] != a.headers["etag"]
    # the defaults written out equal the defaults left out
    d = post(client, "/v1/srt", {"vehicle": BTRAIN, "model": "rigid"})
    e = post(
        client, "/v1/srt", {"vehicle": BTRAIN, "model": "rigid", "targets": {"general": 0.35, "dangerous_goods": 0.4}}
    )
    assert e.headers["x-cache"] == "hit" and e.headers["etag"] == d.headers["etag"]


def test_configured_defaults_are_used_and_keyed():
    with make_client(
        Settings(cache_backend="memory", srt_target_general_g=0.3, srt_target_dangerous_goods_g=0.45)
    ) as c:
        r = post(c, "/v1/srt", {"vehicle": BTRAIN, "model": "rigid"})
        out = r.json()
        assert [(t["name"], t["target_g"], t["meets"]) for t in out["targets"]] == [
            ("general", 0.3, True),
            ("dangerous_goods", 0.45, True),
        ]
        assert out["targets"][1]["margin_g"] == pytest.approx(RIGID_SRT - 0.45, rel=1e-12)
    with make_client() as default:
        other = post(default, "/v1/srt", {"vehicle": BTRAIN, "model": "rigid"})
    # a shared Redis between differently configured workers never serves the other's targets
    assert other.headers["etag"] != r.headers["etag"]


def test_embedded_srt_results_carry_the_targets(shared_client):
    speed = post(shared_client, "/v1/curve-speed", {"radius_m": 100, "vehicle": BTRAIN, "targets": {"x": 0.2}}).json()
    assert [t["name"] for t in speed["srt_result"]["targets"]] == ["x"]
    check_consistent(speed["srt_result"])
    radius = post(
        shared_client, "/v1/min-radius", {"design_speed_kmh": 60, "superelevation_percent": 8, "vehicle": BTRAIN}
    ).json()
    assert [t["name"] for t in radius["srt_result"]["targets"]] == ["general", "dangerous_goods"]
    check_consistent(radius["srt_result"])


def test_targets_with_a_given_srt_are_refused(shared_client):
    p = post(shared_client, "/v1/curve-speed", {"radius_m": 100, "srt": 0.3, "targets": {"x": 0.2}}, 422).json()
    assert p["errors"][0]["field"] == "targets"


@pytest.mark.parametrize(
    ("targets", "field"),
    [
        ({}, "targets"),
        ({"General": 0.35}, "targets.General.[key]"),
        ({"general": 0}, "targets.general"),
        ({"general": 2.5}, "targets.general"),
        ({f"t{i}": 0.3 for i in range(11)}, "targets"),
    ],
)
def test_bad_targets_are_a_422_naming_them(shared_client, targets, field):
    p = post(shared_client, "/v1/srt", {"vehicle": BTRAIN, "targets": targets}, 422).json()
    assert field in [e["field"] for e in p["errors"]]
