# syntax=docker/dockerfile:1
# rollover HTTP service. Build: docker build -t rollover .   Run: docker run -p 8000:8000 rollover
# Debian slim (not Alpine: numpy and scipy have manylinux wheels for glibc, none for musl).

# ---- build stage: a virtualenv with the dependencies, then the project ------------------------------
FROM python:3.11-slim AS build
ENV PIP_NO_CACHE_DIR=1 PIP_DISABLE_PIP_VERSION_CHECK=1
WORKDIR /src
RUN python -m venv /opt/venv
# dependencies layer first: it is rebuilt only when pyproject.toml changes, not on every source edit
COPY pyproject.toml ./
RUN /opt/venv/bin/python -c "import tomllib; print('\n'.join(tomllib.load(open('pyproject.toml', 'rb'))['project']['dependencies']))" > requirements.txt \
    && /opt/venv/bin/pip install -r requirements.txt
# then the source, installed into the same virtualenv (dependencies already satisfied)
COPY README.md ./
COPY engine ./engine
COPY app ./app
RUN /opt/venv/bin/pip install --no-deps .

# ---- runtime stage: the virtualenv only, as a non-root user -----------------------------------------
FROM python:3.11-slim
RUN groupadd --system --gid 10001 rollover && useradd --system --uid 10001 --gid rollover --no-create-home rollover
COPY --from=build /opt/venv /opt/venv
ENV PATH="/opt/venv/bin:$PATH" PYTHONUNBUFFERED=1 PYTHONDONTWRITEBYTECODE=1
WORKDIR /srv
USER rollover
EXPOSE 8000
HEALTHCHECK --interval=30s --timeout=3s CMD ["python", "-c", "import urllib.request; urllib.request.urlopen('http://127.0.0.1:8000/healthz', timeout=2)"]
# the README's serve command (uvicorn app.main:app --port 8000), bound to all interfaces inside the container;
# one process per container: scale with replicas sharing Redis (ROLLOVER_CACHE_BACKEND=redis, ROLLOVER_REDIS_URL)
CMD ["uvicorn", "app.main:app", "--host", "0.0.0.0", "--port", "8000"]
