# syntax=docker/dockerfile:1
# rollover HTTP service. Build: docker build -t rollover .   Run: docker run -p 8000:8000 rollover
# README "Deployment": workers, the database volume, pinning the base image by digest, regenerating the lock.
# Debian slim (not Alpine: numpy and scipy have manylinux wheels for glibc, none for musl). Both stages use the SAME
# exact tag: the virtualenv's python is a symlink to the base image's /usr/local/bin/python3.11.
# BASE_IMAGE is a build argument so that scripts/image/check.sh can build this file on a stand-in base where the
# official image cannot be pulled (docs/deployment.md), or a digest be given; a plain `docker build` uses this tag.
ARG BASE_IMAGE=python:3.11.17-slim-bookworm

# ---- build stage: a virtualenv from the lock, then the project ---------------------------------------------------
FROM ${BASE_IMAGE} AS build
ENV PIP_NO_CACHE_DIR=1 PIP_DISABLE_PIP_VERSION_CHECK=1 PIP_ROOT_USER_ACTION=ignore
WORKDIR /src
# a C compiler for the project's compiled modules (app.formats._rowwriter, the writer of result rows, and
# app.formats._xsectscan, the reading of a LandXML's design cross sections: setup.py),
# in this stage only: the runtime stage never has it. The official image has Python's headers; a base without them
# (the stand-in of scripts/image/check.sh: Debian's python3) gets its python's from Debian's libpython3-dev.
RUN apt-get update \
    && apt-get install -y --no-install-recommends gcc libc6-dev $(python -c 'import os, sysconfig; \
        print("" if os.path.exists(os.path.join(sysconfig.get_paths()["include"], "Python.h")) else "libpython3-dev")') \
    && rm -rf /var/lib/apt/lists/*
# a virtualenv without pip: the base image's pip installs into it (pip --python), so the venv never holds an installer
RUN python -m venv --without-pip /opt/venv
# WHEELHOUSE (empty by default: pip reads the package index) names a directory of wheels mounted into the build, for
# a build without the index (scripts/image/check.sh: buildah bud --volume DIR:/wheelhouse:ro --build-arg
# WHEELHOUSE=/wheelhouse). Either way the dependency install checks every file against the lock's sha256.
ARG WHEELHOUSE=""
# dependency layer: only the lock is copied, so it is rebuilt only when the lock changes (scripts/lock.sh). Every file
# is checked against its locked sha256 and is a wheel (nothing compiled here). The numpy and scipy test suites
# (about 50 MB) are left out of the image: they are never imported by the service.
COPY requirements/runtime.txt requirements/runtime.txt
RUN pip --python /opt/venv/bin/python install --require-hashes --no-deps --only-binary=:all: \
        ${WHEELHOUSE:+--no-index --find-links "$WHEELHOUSE"} -r requirements/runtime.txt \
    && find /opt/venv/lib/python3.11/site-packages/numpy /opt/venv/lib/python3.11/site-packages/scipy \
        -depth -type d -name tests -exec rm -rf {} +
# project layer: a change to the code rebuilds only this (a few hundred kilobytes); pip builds it with the
# setuptools pyproject.toml asks for (from the index, or from the wheelhouse). The compiled modules are optional to
# setup.py (a machine without a compiler still installs, with the slower Python writer and scan); here they must be.
COPY pyproject.toml setup.py README.md ./
COPY engine ./engine
COPY app ./app
RUN pip --python /opt/venv/bin/python install ${WHEELHOUSE:+--no-index --find-links "$WHEELHOUSE"} --no-deps . \
    && /opt/venv/bin/python -I -c 'import app.formats._rowwriter, app.formats._xsectscan'

# ---- runtime stage: the virtualenv only, as a non-root user -------------------------------------------------------
FROM ${BASE_IMAGE}
# no installer in the runtime image: the base image's pip, setuptools and wheel and ensurepip's bundled copies go
# (the virtualenv never had them); then the service's user and its data directory
RUN python -m pip uninstall --yes --quiet --disable-pip-version-check pip setuptools wheel \
    && rm -rf /usr/local/lib/python3.11/ensurepip/_bundled \
    && groupadd --system --gid 10001 rollover \
    && useradd --system --uid 10001 --gid rollover --no-create-home --home-dir /nonexistent rollover \
    && install -d -o rollover -g rollover -m 0750 /var/lib/rollover
COPY --from=build /opt/venv /opt/venv
# the catalog's SQLite database (used when ROLLOVER_API_KEYS is set) lives on the volume, owned by the service's user
ENV PATH="/opt/venv/bin:$PATH" PYTHONUNBUFFERED=1 PYTHONDONTWRITEBYTECODE=1 \
    ROLLOVER_DATABASE_URL=sqlite:////var/lib/rollover/rollover.db
VOLUME ["/var/lib/rollover"]
# an empty directory the service cannot write to: uvicorn puts its working directory first on sys.path
WORKDIR /srv
USER rollover
EXPOSE 8000
# HEALTHCHECK is a Docker image-format instruction: podman/buildah drop it from OCI images (build with --format docker)
HEALTHCHECK --interval=30s --timeout=3s CMD ["python", "-c", "import urllib.request; urllib.request.urlopen('http://127.0.0.1:8000/healthz', timeout=2)"]
# the README's serve command bound to all interfaces, on uvloop and httptools (uvicorn[standard]). Workers:
# WEB_CONCURRENCY=N (read by uvicorn) with ROLLOVER_CACHE_BACKEND=redis; or one worker per container and replicas.
CMD ["uvicorn", "app.main:app", "--host", "0.0.0.0", "--port", "8000", "--loop", "uvloop", "--http", "httptools"]
