"""A road file's rows through a job (app/jobs/op_alignments.py): the bend columns are stored with each part's curves
and results, the reading with the job, and the result is the synchronous answer byte for byte, in JSON and CSV,
split over several parts."""

from __future__ import annotations

import random

import pytest

from app.settings import Settings
from tests.landxml_writer import landxml
from tests.road.test_landxml_files import _design

from .conftest import make_client, wait_for


@pytest.mark.parametrize("accept", [None, "text/csv"])
def test_a_landxml_job_is_the_synchronous_answer(accept):
    design = _design(random.Random(11), n_bends=7)
    req = {"vehicle": "table16-btrain", "landxml": {"document": landxml(design, "foot"), "superelevation_percent": 5.0}}
    headers = {"Accept": accept} if accept else None
    with make_client(Settings(jobs_part_size=3)) as c:
        r = c.post("/v1/jobs", json={"operation": "alignments.assess", "request": req})
        assert r.status_code == 202, r.text
        status = wait_for(c, r.headers["location"])
        assert status["status"] == "done" and status["parts"]["total"] > 1
        job = c.get(r.headers["location"] + "/result", headers=headers)
        sync = c.post("/v1/alignments/assess", json=req, headers=headers)
    assert job.status_code == sync.status_code == 200
    assert job.content == sync.content
    if accept is None:
        assert b'"reading":{"format":"LandXML 1.2"' in job.content and b'"grade_source":"profile"' in job.content
