"""Alignment assessment: every horizontal curve of a road for every vehicle (``POST /v1/alignments/assess`` and the
raw CSV and LandXML uploads, :mod:`~app.alignments.router`). The JSON curves are read into columns by
:mod:`~app.alignments.curves`, the uploads' queries are :mod:`~app.alignments.uploads`, the assessment is
:mod:`~app.alignments.service` and an assessed row is rendered in :mod:`~app.alignments.rows`."""
