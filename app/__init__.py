"""rollover HTTP service: a thin FastAPI layer over :mod:`engine` (schemas, routers, cache, settings).

Importing it sets ``OPENBLAS_NUM_THREADS=1`` unless the environment already sets it: the service parallelises
large batches on its own solver threads (``ROLLOVER_SOLVE_THREADS``) and answers many small requests at once, and
OpenBLAS's own threads on the engine's 20 x 20 matrices cost far more than they bring (measured in
docs/dynamics.md: a PBS screening of 5-10 ms on one thread against 8-280 ms with the library's default threads; the
static paths no faster with them). It must be set before numpy loads OpenBLAS, hence here, the first module of the
service that any entry point (uvicorn, the job worker) imports.
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
