"""A road file's rows through a job (app/jobs/op_alignments.py): the bend columns are stored with each part's curves
and results, the reading with the job, and the result is the synchronous answer byte for byte, in JSON and CSV,
split over several parts."""

from __future__ import annotations

import random

import pytest

from tests.landxml_writer import landxml
from tests.road.test_landxml_files import _design

from .conftest import job_and_sync


@pytest.mark.parametrize("accept", [None, "text/csv"])
def test_a_landxml_job_is_the_synchronous_answer(accept):
    design = _design(random.Random(11), n_bends=7)
    req = {"vehicle": "table16-btrain", "landxml": {"document": landxml(design, "foot"), "superelevation_percent": 5.0}}
    _, job, sync = job_and_sync(req, accept, 3)
    assert job.content == sync.content
    if accept is None:
        assert b'"reading":{"format":"LandXML 1.2"' in job.content and b'"grade_source":"profile"' in job.content


@pytest.mark.parametrize("accept", [None, "text/csv"])
def test_the_advice_of_a_job_split_in_parts_is_the_synchronous_answers(accept):
    """The speed profile and the shared signs run across the parts (app/alignments/advice.py): a job computes each
    vehicle's advice over the whole alignment from its parts, so its rows and profile are the synchronous answer's
    byte for byte; two vehicles, a posted speed (a profile exists) and the metric plaque."""
    design = _design(random.Random(7), n_bends=9)
    document = landxml(design)
    req = {
        "vehicles": ["table16-btrain", "table23-semitrailer"],
        "landxml": {"document": document, "superelevation_percent": 5.0, "posted_speed_kmh": 90.0},
        "units": "metric",
        "deceleration_mps2": 2.5,
    }
    _, job, sync = job_and_sync(req, accept, 4)
    assert job.content == sync.content
    if accept is None:
        vehicles = sync.json()["vehicles"]
        assert all(len(v["speed_profile"]) > 2 for v in vehicles)
        assert any(r["approach_speed_kmh"] is not None for r in vehicles[0]["rows"])
