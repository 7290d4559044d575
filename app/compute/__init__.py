"""How a computed answer is produced and kept: the result cache (:mod:`~app.compute.cache`), the coalescer of
concurrent one-threshold solves (:mod:`~app.compute.coalescer`), the solver threads of large batches
(:mod:`~app.compute.solvers`) and the answer types with the cache-or-compute step (:mod:`~app.compute.results`).
Nothing here knows a feature's schemas."""
