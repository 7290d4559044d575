"""The compiled modules: app.formats._rowwriter (app/formats/csrc/rowwriter.c), the C writer of result rows, and
app.formats._xsectscan (app/formats/csrc/xsectscan.c), the C reading of a LandXML's design cross sections.

Everything else is in pyproject.toml. Both modules are optional: where no C compiler is found the build goes on
without them (a warning) and app.formats.segments writes the rows in Python, byte for byte the same text, slower
(docs/jobs.md), and app.formats.landxml reads the cross sections by its Python scan, the same numbers, slower
(docs/uploads.md). Under CI=true the suite fails when a module is missing (tests/api/test_rowwriter.py,
tests/road/test_landxml_scan.py).
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
        ),
        Extension(
            "app.formats._xsectscan",
            sources=["app/formats/csrc/xsectscan.c"],
            extra_compile_args=["-O2"],
            optional=True,
        ),
    ]
)
