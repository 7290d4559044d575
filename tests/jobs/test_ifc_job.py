"""An IFC 4.3 document through a job (app/jobs/op_alignments.py, the request's ``ifc``): the result is the
synchronous answer byte for byte, in JSON and CSV, split over several parts."""

from __future__ import annotations

import pytest

from tests.api.test_ifc_api import random_pair

from .conftest import job_and_sync, make_client


@pytest.mark.parametrize("accept", [None, "text/csv"])
def test_an_ifc_job_is_the_synchronous_answer(accept):
    _, ifc, _ = random_pair(11, n_bends=7)
    req = {"vehicle": "table16-btrain", "ifc": {"document": ifc, "posted_speed_kmh": 80.0}}
    _, job, sync = job_and_sync(req, accept, 3)
    assert job.content == sync.content
    if accept is None:
        assert b'"reading":{"format":"IFC 4.3 (IFC4X3_ADD2)"' in job.content
        assert b'"superelevation_source":"cross-sections"' in job.content


def test_an_ifc_job_with_a_refused_schema_names_it():
    req = {"vehicle": "table16-btrain", "ifc": {"document": random_pair(3)[1].replace("IFC4X3_ADD2", "IFC4X3_RC3")}}
    with make_client() as c:
        r = c.post("/v1/jobs", json={"operation": "alignments.assess", "request": req})
    assert r.status_code == 422, r.text
    (e,) = r.json()["errors"]
    assert e["field"] == "request.ifc.document.FILE_SCHEMA" and "'IFC4X3_RC3'" in e["message"]
