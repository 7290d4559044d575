"""Long batches as jobs: ``/v1/jobs`` (:mod:`app.jobs.router`, its models :mod:`app.jobs.schemas`, what it does
:mod:`app.jobs.service`), the operations they run (:mod:`app.jobs.operations`), the store (:mod:`app.jobs.store` over
:mod:`app.jobs.kv`), the backends (:mod:`app.jobs.backends`: in-process by default, Redis + RQ for many workers) and the
worker command (``python -m app.jobs.worker``). See docs/jobs.md.
"""
