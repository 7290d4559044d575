"""The README's two commands, the Dockerfile and .ci/run agree with each other and with pyproject.toml.

There is no Docker engine on the CI machines, so the Dockerfile is checked by parsing it.
"""

from __future__ import annotations

import json
import os
import re
import shlex
import tomllib

import pytest

from .conftest import ROOT

README = (ROOT / "README.md").read_text(encoding="utf-8")
DOCKERFILE = (ROOT / "Dockerfile").read_text(encoding="utf-8")
CI_RUN = ROOT / ".ci" / "run"
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))

SERVE = "pip install -e . && uvicorn app.main:app --host 127.0.0.1 --port 8000"
TEST = "pip install -e '.[test]' && python -m pytest"


def bash_blocks(text: str) -> list[str]:
    return re.findall(r"```bash\n(.*?)```", text, flags=re.S)


def dockerfile_instructions() -> list[tuple[str, str]]:
    text = re.sub(r"\\\n", " ", DOCKERFILE)
    out = []
    for line in text.splitlines():
        line = line.strip()
        if line and not line.startswith("#"):
            word, _, rest = line.partition(" ")
            out.append((word.upper(), rest.strip()))
    return out


def stages() -> list[list[tuple[str, str]]]:
    result: list[list[tuple[str, str]]] = []
    for word, rest in dockerfile_instructions():
        if word == "FROM":
            result.append([])
        if result:
            result[-1].append((word, rest))
    return result


def uvicorn_args(command: str) -> dict[str, str]:
    """The app object and options of the uvicorn call in a shell command (or an exec-form argv)."""
    argv = shlex.split(command.split("&&")[-1]) if isinstance(command, str) else command
    i = argv.index("uvicorn")
    args = argv[i + 1 :]
    opts = {"app": args[0]}
    for flag, value in zip(args[1::2], args[2::2], strict=False):
        opts[flag] = value
    return opts


def test_readme_gives_the_two_commands_in_their_own_blocks():
    blocks = [b.strip() for b in bash_blocks(README)]
    assert SERVE in blocks
    assert TEST in blocks


def test_readme_test_command_runs_the_whole_suite():
    # plain pytest from the repo root: testpaths = ["tests"] covers the engine and the API tests
    assert PYPROJECT["tool"]["pytest"]["ini_options"]["testpaths"] == ["tests"]
    assert "python -m pytest" in TEST and " -k " not in TEST and " -m " not in TEST.replace("python -m", "")


def test_readme_has_a_curl_example_per_endpoint():
    for method, path in [
        ("GET", "/healthz"),
        ("GET", "/metrics"),
        ("GET", "/v1/vehicles"),
        ("GET", "/v1/vehicles/table16-btrain"),
        ("GET", "/v1/models"),
        ("POST", "/v1/srt"),
        ("POST", "/v1/curve-speed"),
        ("POST", "/v1/min-radius"),
        ("POST", "/v1/srt/limits"),
        ("POST", "/v1/srt/sweep"),
        ("POST", "/v1/alignments/assess"),
        ("POST", "/v1/alignments/assess/csv"),
        ("POST", "/v1/alignments/assess/landxml"),
        ("POST", "/v1/plots/tire-loads"),
        ("POST", "/v1/plots/min-radius"),
    ]:
        # a URL with a query string is quoted for the shell
        pattern = rf"\$ curl -s[i]? (-X POST )?'?http://127\.0\.0\.1:8000{re.escape(path)}[ |'?]"
        assert re.search(pattern, README), (method, path)
        if method == "POST":
            assert re.search(rf"-X POST '?http://127\.0\.0\.1:8000{re.escape(path)}[ '?]", README), path
    # each example shows its output (a line after the command that is not another command)
    examples = re.findall(r"```console\n\$ (.*?)```", README, flags=re.S)
    assert len(examples) >= 8 and all(len(e.strip().splitlines()) >= 2 for e in examples)


def test_readme_documents_every_setting():
    from app.settings import Settings

    for name in Settings.model_fields:
        assert f"ROLLOVER_{name.upper()}" in README
    assert "ROLLOVER_CACHE_BACKEND=redis ROLLOVER_REDIS_URL=" in README and "--workers" in README


def test_dockerfile_is_multi_stage_slim_debian():
    froms = [rest for word, rest in dockerfile_instructions() if word == "FROM"]
    assert len(froms) >= 2
    for image in froms:
        base = image.split()[0]
        assert base.startswith("python:3.11-slim") and "alpine" not in base


def test_dockerfile_runs_as_a_non_root_user():
    final = stages()[-1]
    users = [rest for word, rest in final if word == "USER"]
    assert users and users[-1] not in ("root", "0")
    # the USER comes before the CMD
    words = [w for w, _ in final]
    assert words.index("USER") < words.index("CMD")


def test_dockerfile_cmd_is_exec_form_and_runs_the_readme_server():
    cmds = [rest for word, rest in dockerfile_instructions() if word == "CMD"]
    argv = json.loads(cmds[-1])  # exec form: a JSON array
    assert isinstance(argv, list) and argv[0] == "uvicorn"
    docker = uvicorn_args(argv)
    readme = uvicorn_args(SERVE)
    assert docker["app"] == readme["app"] == "app.main:app"
    assert docker["--port"] == readme["--port"] == "8000"
    assert docker["--host"] == "0.0.0.0" and readme["--host"] == "127.0.0.1"
    exposed = [rest for word, rest in dockerfile_instructions() if word == "EXPOSE"]
    assert exposed == ["8000"]


def test_dockerfile_installs_the_dependencies_from_pyproject_before_the_source():
    build = stages()[0]
    copies = [(i, rest) for i, (word, rest) in enumerate(build) if word == "COPY"]
    runs = [(i, rest) for i, (word, rest) in enumerate(build) if word == "RUN"]
    pyproject_copy = next(i for i, rest in copies if rest.split()[0] == "pyproject.toml")
    source_copies = [i for i, rest in copies if rest.split()[0] in ("app", "engine")]
    assert {rest.split()[0] for _, rest in copies} >= {"pyproject.toml", "app", "engine", "README.md"}
    deps_install = next(i for i, rest in runs if "pyproject.toml" in rest and "pip install" in rest)
    assert pyproject_copy < deps_install < min(source_copies)
    # the dependency list is read from pyproject's [project].dependencies, not restated by hand
    assert "['project']['dependencies']" in build[deps_install][1]
    # then the project itself is installed (packages engine* and app*) after the source is copied
    project_install = next(i for i, rest in runs if re.search(r"pip install (--no-deps )?\.$", rest))
    assert project_install > max(source_copies)
    assert PYPROJECT["tool"]["setuptools"]["packages"]["find"]["include"] == ["engine*", "app*"]
    # the runtime stage takes the installed virtualenv and puts it on the PATH, so `uvicorn` is the one installed
    final = stages()[-1]
    assert any(w == "COPY" and "--from=build" in rest for w, rest in final)
    assert any(w == "ENV" and "/opt/venv/bin" in rest for w, rest in final)


def test_readme_serve_command_installs_the_project_from_pyproject():
    assert SERVE.startswith("pip install -e . && ")
    assert {"fastapi", "uvicorn"} <= {re.split(r"[<>=\[]", d)[0] for d in PYPROJECT["project"]["dependencies"]}


def test_ci_run_installs_redis_and_runs_the_readme_test_command():
    text = CI_RUN.read_text(encoding="utf-8")
    assert text.startswith("#!/usr/bin/env bash")
    assert "set -euo pipefail" in text
    assert "apt-get update" in text and "apt-get install -y" in text and "redis-server" in text
    lines = [line.strip() for line in text.splitlines() if line.strip() and not line.strip().startswith("#")]
    assert lines[-1] == TEST
    if os.name == "posix":
        assert os.access(CI_RUN, os.X_OK), ".ci/run must be executable"


@pytest.mark.parametrize("name", ["Dockerfile", ".ci/run", "README.md"])
def test_files_exist(name):
    assert (ROOT / name).is_file()
