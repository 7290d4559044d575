"""The one compiled module: app.formats._rowwriter (app/formats/csrc/rowwriter.c), the C writer of result rows.

Everything else is in pyproject.toml. The module is optional: where no C compiler is found the build goes on
without it (a warning) and app.formats.segments writes the rows in Python, byte for byte the same text, slower
(docs/jobs.md). Under CI=true the suite fails when the module is missing (tests/api/test_segments.py).
"""

from setuptools import Extension, setup

setup(
    ext_modules=[
        Extension(
            "app.formats._rowwriter",
            sources=["app/formats/csrc/rowwriter.c"],
            include_dirs=["app/formats/csrc"],
            extra_compile_args=["-O2"],
            optional=True,
        )
    ]
)
