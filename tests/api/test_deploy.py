"""The README's two commands, the Dockerfile, the lock files and .ci/run agree with each other and with pyproject.toml.

There is no Docker engine on the CI machines: the Dockerfile is checked here by parsing it, and built and run with
buildah on a stand-in base by scripts/image/check.sh, which .ci/run calls after this suite (docs/deployment.md).
"""

from __future__ import annotations

import fnmatch
import json
import os
import re
import shlex
import tomllib

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

from .conftest import ROOT

README = (ROOT / "README.md").read_text(encoding="utf-8")
EXAMPLES = (ROOT / "docs" / "examples.md").read_text(encoding="utf-8")
SERVICE_DOC = (ROOT / "docs" / "service.md").read_text(encoding="utf-8")
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


#: operations without a curl example in docs/examples.md, and where they are shown instead
NOT_IN_EXAMPLES = {
    # the catalog needs a key and a database: walked through in docs/catalog.md
    ("POST", "/v1/vehicles"): "docs/catalog.md",
    ("GET", "/v1/vehicles/saved"): "docs/catalog.md",
    ("PUT", "/v1/vehicles/{id}"): "docs/catalog.md",
    ("DELETE", "/v1/vehicles/{id}"): "docs/catalog.md",
    ("POST", "/v1/fleets"): "docs/catalog.md",
    ("GET", "/v1/fleets"): "docs/catalog.md",
    ("GET", "/v1/fleets/{id}"): "docs/catalog.md",
    ("PUT", "/v1/fleets/{id}"): "docs/catalog.md",
    ("DELETE", "/v1/fleets/{id}"): "docs/catalog.md",
    # jobs answer with a random id and run asynchronously: docs/api.md, docs/jobs.md
    ("POST", "/v1/jobs"): "docs/api.md: Long batches as jobs",
    ("GET", "/v1/jobs/{job_id}"): "docs/api.md: Long batches as jobs",
    ("GET", "/v1/jobs/{job_id}/result"): "docs/api.md: Long batches as jobs",
    ("DELETE", "/v1/jobs/{job_id}"): "docs/api.md: Long batches as jobs",
    # the same body as an operation that is shown, or a part of one that is
    ("POST", "/v1/plots/llt"): "the note under the tire-loads example",
    ("POST", "/v1/plots/roll"): "the note under the tire-loads example",
    ("POST", "/v1/plots/cg-path"): "the note under the tire-loads example",
    ("GET", "/v1/components/tyres"): "the /v1/components example (its tyres)",
    ("GET", "/v1/components/suspensions"): "the /v1/components example (its suspensions)",
    ("GET", "/v1/design-standards/{id}"): "the /v1/design-standards example (one of its standards)",
    ("POST", "/v1/superelevation/table"): "docs/api.md: Design standards",
    # the alignment assessment's body (a road file's stations): docs/api.md, docs/advisory.md section 4
    ("POST", "/v1/plots/speed-profile"): "docs/api.md: Road-design tools (the alignment assessment's body)",
}


def test_the_examples_have_a_curl_example_per_operation_of_the_spec():
    """Every operation of the committed spec has a curl example with its output in docs/examples.md (written by
    scripts/readme_examples.py from real answers), or says above where it is shown instead: a new endpoint fails
    here until it is documented."""
    assert "docs/examples.md" in README
    spec = json.loads((ROOT / "openapi" / "openapi.json").read_text(encoding="utf-8"))
    operations = {
        (m.upper(), p) for p, item in spec["paths"].items() for m in item if m in ("get", "post", "put", "delete")
    }
    assert set(NOT_IN_EXAMPLES) <= operations  # no stale exception
    shown = [op for op in sorted(operations) if op not in NOT_IN_EXAMPLES]
    assert len(shown) >= 20
    for method, path in shown:
        preset = "btrain-table16" if path.startswith("/v1/combinations") else "table16-btrain"
        concrete = path.replace("{id}", preset)
        # a URL with a query string is quoted for the shell
        pattern = rf"\$ curl -s[i]? (-X {method} )?'?http://127\.0\.0\.1:8000{re.escape(concrete)}[ |'?]"
        assert re.search(pattern, EXAMPLES), (method, path)
        if method == "POST":
            assert re.search(rf"-X POST '?http://127\.0\.0\.1:8000{re.escape(concrete)}[ '?]", EXAMPLES), path
    # each example shows its output (a line after the command that is not another command)
    examples = re.findall(r"```console\n\$ (.*?)```", EXAMPLES, flags=re.S)
    assert len(examples) >= 20 and all(len(e.strip().splitlines()) >= 2 for e in examples)


@pytest.mark.slow
def test_the_examples_are_what_the_app_answers_today():
    """The block scripts/readme_examples.py writes is the one committed: an answer that changed fails here (run in a
    fresh process: the metrics example counts this process's cache lookups)."""
    import subprocess
    import sys

    done = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "readme_examples.py")], capture_output=True, text=True, cwd=ROOT
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert _found_to_the_last_digits(done.stdout.rstrip("\n"), EXAMPLES), (
        "docs/examples.md is stale: python scripts/readme_examples.py --write"
    )


@pytest.mark.slow
def test_the_readme_examples_are_what_the_app_answers_today():
    """The README's quick-start answers are written by the same script from real answers, to the last digit."""
    import subprocess
    import sys

    done = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "readme_examples.py"), "--readme"],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    block = done.stdout.rstrip("\n")
    assert block.count("$ curl") >= 2
    stale = "the README's examples are stale: python scripts/readme_examples.py --write"
    assert _found_to_the_last_digits(block, README), stale


#: a number as the answers print it (repr of a float, or an integer)
_NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def _found_to_the_last_digits(block: str, doc: str) -> bool:
    """``block`` is in ``doc`` word for word, except that a float printed with all its digits may differ from the
    committed one in its last two (relative 1e-13): the engine's iterative solves and libm's transcendental functions
    round differently on other CPUs (seen between two machines of this project: the 14th digit of a 3D SRT), while
    any real change of an answer moves digits far above that."""
    if block in doc:
        return True
    pieces = _NUMBER.split(block)
    numbers = _NUMBER.findall(block)
    start = doc.find(pieces[0])
    while start >= 0:
        candidate = re.match(
            "".join(re.escape(p) + (f"({_NUMBER.pattern})" if k < len(numbers) else "") for k, p in enumerate(pieces)),
            doc[start:],
            flags=re.S,
        )
        if candidate and all(_close(a, b) for a, b in zip(numbers, candidate.groups(), strict=True)):
            return True
        start = doc.find(pieces[0], start + 1)
    return False


def _close(a: str, b: str) -> bool:
    if a == b:
        return True
    digits = len(re.sub(r"e.*|[^0-9]", "", a).lstrip("0"))
    if digits < 15:  # a number printed short (rounded by the example) must match exactly
        return False
    x, y = float(a), float(b)
    return abs(x - y) <= 1e-13 * max(abs(x), abs(y))


def test_readme_stays_a_newcomer_s_page_and_links_the_reference():
    """About 250 lines (issue 21): what it does, the two commands, the library, the layout, tests, links; the
    reference lives in docs/ and every docs/ page the README links exists."""
    assert len(README.splitlines()) <= 300
    for link in re.findall(r"\]\((docs/[^)#]+)", README):
        assert (ROOT / link).is_file(), link
    for section in ("## Quick start", "## Use from Python", "## Layout", "## Tests"):
        assert section in README
    assert 'python -m pytest -m "not slow"' in README


def test_the_service_page_documents_every_setting():
    from app.settings import Settings

    assert "docs/service.md" in README
    for name in Settings.model_fields:
        assert f"ROLLOVER_{name.upper()}" in SERVICE_DOC, name
    assert "ROLLOVER_CACHE_BACKEND=redis ROLLOVER_REDIS_URL=" in SERVICE_DOC and "--workers" in SERVICE_DOC


#: an exact version tag of the official image, Debian slim (optionally with its digest)
BASE_IMAGE = re.compile(r"python:3\.11\.\d+-slim-(bookworm|trixie)(@sha256:[0-9a-f]{64})?")


def global_args() -> dict[str, str]:
    """The ARGs declared before the first FROM (the only ones a FROM line can use), with their defaults."""
    args = {}
    for word, rest in dockerfile_instructions():
        if word == "FROM":
            break
        if word == "ARG":
            name, _, default = rest.partition("=")
            args[name] = default
    return args


def test_dockerfile_is_multi_stage_slim_debian_pinned_to_one_exact_tag():
    froms = [rest.split()[0] for word, rest in dockerfile_instructions() if word == "FROM"]
    assert len(froms) >= 2
    # every stage is FROM the one build argument (scripts/image/check.sh gives a stand-in), so all stages have the
    # same base: the runtime stage runs the build stage's virtualenv, whose python is a symlink to the base image's
    # interpreter. Its default is the pinned official image: a plain `docker build` uses that
    assert set(froms) == {"${BASE_IMAGE}"}
    image = global_args()["BASE_IMAGE"]
    assert BASE_IMAGE.fullmatch(image), image  # not a moving tag such as python:3.11-slim


def test_dockerfile_runs_as_a_non_root_user():
    final = stages()[-1]
    users = [rest for word, rest in final if word == "USER"]
    assert users and users[-1] not in ("root", "0")
    # the USER comes before the CMD
    words = [w for w, _ in final]
    assert words.index("USER") < words.index("CMD")


def test_dockerfile_cmd_is_exec_form_and_runs_the_readme_server_on_uvloop_and_httptools():
    cmds = [rest for word, rest in dockerfile_instructions() if word == "CMD"]
    argv = json.loads(cmds[-1])  # exec form: a JSON array
    assert isinstance(argv, list) and argv[0] == "uvicorn"
    docker = uvicorn_args(argv)
    readme = uvicorn_args(SERVE)
    assert docker["app"] == readme["app"] == "app.main:app"
    assert docker["--port"] == readme["--port"] == "8000"
    assert docker["--host"] == "0.0.0.0" and readme["--host"] == "127.0.0.1"
    assert docker["--loop"] == "uvloop" and docker["--http"] == "httptools"
    # which uvicorn[standard] brings, and the lock the image installs has
    assert "uvicorn[standard]" in {re.split(r"[<>=]", d)[0] for d in PYPROJECT["project"]["dependencies"]}
    assert {"uvloop", "httptools"} <= set(locked("runtime"))
    exposed = [rest for word, rest in dockerfile_instructions() if word == "EXPOSE"]
    assert exposed == ["8000"]


def test_dockerfile_installs_the_locked_dependencies_in_their_own_layer_before_the_source():
    build = stages()[0]
    copies = [(i, rest.split()) for i, (word, rest) in enumerate(build) if word == "COPY"]
    runs = [(i, rest) for i, (word, rest) in enumerate(build) if word == "RUN"]
    # the first COPY brings the runtime lock alone: the dependency layer depends on nothing else
    first_copy, sources = copies[0]
    assert sources[:-1] == ["requirements/runtime.txt"]
    deps = next(i for i, rest in runs if "-r requirements/runtime.txt" in rest)
    assert "--require-hashes" in build[deps][1] and "--only-binary=:all:" in build[deps][1]
    later = [i for i, src in copies if {"pyproject.toml", "app", "engine"} & set(src[:-1])]
    assert first_copy < deps < min(later)
    assert {s for _, src in copies for s in src[:-1]} >= {"pyproject.toml", "README.md", "app", "engine"}
    # then the project itself (packages engine* and app*) without dependencies, after its source is copied
    project = next(i for i, rest in runs if re.search(r"install .*--no-deps \.( |$)", rest))
    assert project > max(later)
    # the compiled modules (setup.py makes them optional) are required in the image: their import ends the install
    imports = "/opt/venv/bin/python -I -c 'import app.formats._rowwriter, app.formats._xsectscan'"
    assert build[project][1].endswith(imports)
    assert any(w == "COPY" and "setup.py" in rest.split() for w, rest in build)
    # the compiler it needs is the build stage's alone
    assert any(w == "RUN" and "apt-get install" in rest and " gcc " in rest for w, rest in build)
    assert not any(w == "RUN" and "gcc" in rest for w, rest in stages()[-1])
    assert PYPROJECT["tool"]["setuptools"]["packages"]["find"]["include"] == ["engine*", "app*"]
    # the runtime stage takes the installed virtualenv and puts it on the PATH, so `uvicorn` is the one installed
    final = stages()[-1]
    assert any(w == "COPY" and "--from=build" in rest and "/opt/venv" in rest for w, rest in final)
    assert any(w == "ENV" and "/opt/venv/bin" in rest for w, rest in final)


def test_the_build_takes_an_optional_wheelhouse_and_checks_every_hash_either_way():
    """WHEELHOUSE (empty by default) adds --no-index --find-links to both installs; --require-hashes stays."""
    import subprocess

    build = stages()[0]
    assert ("ARG", 'WHEELHOUSE=""') in build
    option = '${WHEELHOUSE:+--no-index --find-links "$WHEELHOUSE"}'
    installs = [rest for w, rest in build if w == "RUN" and rest.startswith("pip ") and " install " in rest]
    assert len(installs) == 2 and all(option in rest for rest in installs)
    assert all("--require-hashes" in rest for rest in installs if "-r requirements/runtime.txt" in rest)
    # what the shell makes of it (a RUN is `/bin/sh -c`, its ARGs in the environment)
    for value, argv in [("", []), ("/wheelhouse", ["--no-index", "--find-links", "/wheelhouse"])]:
        done = subprocess.run(
            ["sh", "-c", f'for a in {option}; do echo "$a"; done'],
            env={"WHEELHOUSE": value, "PATH": os.environ.get("PATH", "/usr/bin:/bin")},
            capture_output=True,
            text=True,
            check=True,
        )
        assert done.stdout.splitlines() == argv


def test_the_runtime_image_has_no_installer():
    build, final = stages()[0], stages()[-1]
    # the virtualenv is made without pip (the base image's pip installs into it with --python) ...
    assert any(w == "RUN" and "venv --without-pip /opt/venv" in rest for w, rest in build)
    assert all("/opt/venv/bin/pip " not in rest for _, rest in build)
    # ... and the runtime stage removes the base image's own pip, setuptools and wheel
    uninstall = [rest for w, rest in final if w == "RUN" and "pip uninstall" in rest]
    assert uninstall and all(name in uninstall[0] for name in ("pip", "setuptools", "wheel"))


def test_the_sqlite_database_lives_on_a_volume_owned_by_the_service_user():
    final = stages()[-1]
    env = " ".join(rest for w, rest in final if w == "ENV")
    url = re.search(r"ROLLOVER_DATABASE_URL=sqlite:///(/\S+)", env)
    assert url, "the database URL points into the volume"
    directory = url.group(1).rsplit("/", 1)[0]
    volumes = [v for w, rest in final if w == "VOLUME" for v in json.loads(rest)]
    assert directory in volumes
    user = [rest for w, rest in final if w == "USER"][-1]
    assert any(
        w == "RUN" and re.search(rf"install -d -o {user} -g {user} .*{re.escape(directory)}", rest) for w, rest in final
    )
    # the working directory is not the writable volume: uvicorn puts it first on sys.path
    workdir = [rest for w, rest in final if w == "WORKDIR"][-1]
    assert workdir != directory


def test_dockerignore_keeps_the_context_small_and_lets_through_what_the_build_copies():
    patterns = [
        line.strip() for line in (ROOT / ".dockerignore").read_text().splitlines() if line.strip() and line[0] != "#"
    ]
    assert {".git", ".venv*", "tests"} <= set(patterns)
    sources = [s for w, rest in stages()[0] if w == "COPY" for s in rest.split()[:-1] if not s.startswith("--")]
    for source in sources:
        assert not any(fnmatch.fnmatch(source, p) or source.startswith(p + "/") for p in patterns), source


# ----------------------------------------------------------------------------------------------- the lock


def locked(name: str) -> dict[str, str]:
    """requirements/<name>.txt -> {normalised package name: pinned version}; every pin carries a sha256."""
    text = (ROOT / "requirements" / f"{name}.txt").read_text(encoding="utf-8")
    pins: dict[str, str] = {}
    for entry in re.split(r"\n(?=[A-Za-z0-9])", text.split("\n", 2)[-1]):
        head = entry.split(";")[0].split("\\")[0].strip()
        if "==" not in head:
            continue
        package, version = (p.strip() for p in head.split("=="))
        assert "--hash=sha256:" in entry, f"{name}.txt: {package} has no hash"
        pins.setdefault(canonicalize_name(package), version)
    return pins


@pytest.mark.parametrize(("lock", "extras"), [("runtime", []), ("test", ["test"]), ("dev", ["test", "dev"])])
def test_the_lock_pins_every_dependency_of_pyproject_within_its_range(lock, extras):
    pins = locked(lock)
    wanted = list(PYPROJECT["project"]["dependencies"])
    for extra in extras:
        wanted += PYPROJECT["project"]["optional-dependencies"][extra]
    for line in wanted:
        req = Requirement(line)
        name = canonicalize_name(req.name)
        # a dependency added to pyproject.toml without running scripts/lock.sh fails here
        assert name in pins, f"{req.name} is not in requirements/{lock}.txt: run scripts/lock.sh"
        assert req.specifier.contains(pins[name], prereleases=True), (req, pins[name])
        for extra in req.extras:  # psycopg[binary] -> psycopg-binary, uvicorn[standard] -> uvloop, httptools...
            assert extra != "binary" or f"{name}-binary" in pins


def test_the_three_locks_agree_and_the_runtime_one_holds_no_test_tools():
    runtime, test, dev = locked("runtime"), locked("test"), locked("dev")
    assert runtime.items() <= test.items() <= dev.items()
    assert not {"pytest", "hypothesis", "schemathesis", "ruff"} & set(runtime)
    assert "ruff" in dev


def test_lock_script_regenerates_the_three_files_with_hashes():
    script = ROOT / "scripts" / "lock.sh"
    text = script.read_text(encoding="utf-8")
    assert text.startswith("#!/usr/bin/env bash") and "set -euo pipefail" in text
    assert "--generate-hashes" in text
    for name in ("runtime", "test", "dev"):
        assert f"requirements/{name}.txt" in text
    if os.name == "posix":
        assert os.access(script, os.X_OK)
    assert "scripts/lock.sh" in README


def test_readme_serve_command_installs_the_project_from_pyproject():
    assert SERVE.startswith("pip install -e . && ")
    assert {"fastapi", "uvicorn"} <= {re.split(r"[<>=\[]", d)[0] for d in PYPROJECT["project"]["dependencies"]}


def test_ci_run_installs_redis_and_runs_the_suite_from_the_lock_in_its_own_venv():
    text = CI_RUN.read_text(encoding="utf-8")
    assert text.startswith("#!/usr/bin/env bash")
    assert "set -euo pipefail" in text
    assert "apt-get update" in text and "apt-get install -y" in text and "redis-server" in text
    lines = [line.strip() for line in text.splitlines() if line.strip() and not line.strip().startswith("#")]
    venv = lines.index("python3 -m venv .venv-ci")
    activate, deps, project = lines[venv + 1 : venv + 4]
    assert 'PATH="$PWD/.venv-ci/bin:$PATH"' in activate
    assert deps.startswith("python -m pip install") and "--require-hashes -r requirements/test.txt" in deps
    assert project.startswith("python -m pip install") and project.endswith("--no-deps -e .")
    # then the README test command's second half: the whole suite, and after it the image check
    assert lines[-2] == TEST.split(" && ")[-1] == "python -m pytest"
    assert lines[-1] == "bash scripts/image/check.sh"
    if os.name == "posix":
        assert os.access(CI_RUN, os.X_OK), ".ci/run must be executable"


@pytest.mark.parametrize(
    "name",
    [
        "Dockerfile",
        ".dockerignore",
        ".ci/run",
        "README.md",
        "scripts/lock.sh",
        "scripts/image/check.sh",
        "compose.yaml",
        "docs/deployment.md",
    ],
)
def test_files_exist(name):
    assert (ROOT / name).is_file()


@pytest.mark.slow
def test_the_readme_python_example_prints_what_the_readme_says():
    """The "Use from Python" block runs as written (in a fresh interpreter) and prints the text block under it."""
    import subprocess
    import sys

    section = README.split("## Use from Python", 1)[1].split("\n## ", 1)[0]
    code = re.search(r"```python\n(.*?)```", section, flags=re.S).group(1)
    printed = re.search(r"```text\n(.*?)```", section, flags=re.S).group(1)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout == printed


# ------------------------------------------------------------------------------------- the image, built and run
IMAGE_CHECK = ROOT / "scripts" / "image" / "check.sh"


def test_the_image_check_builds_the_dockerfile_on_a_stand_in_and_runs_the_image_s_own_cmd():
    """scripts/image/check.sh (run by .ci/run) is the image built and run; here only what it is made of."""
    text = IMAGE_CHECK.read_text(encoding="utf-8")
    assert text.startswith("#!/usr/bin/env bash") and "set -euo pipefail" in text
    if os.name == "posix":
        assert os.access(IMAGE_CHECK, os.X_OK)
    assert "debootstrap --variant=minbase" in text and "python3 -m venv /usr/local" in text
    assert "buildah bud --isolation chroot --network host --format docker" in text
    for arg in (
        "--build-arg BASE_IMAGE=",
        "--build-arg WHEELHOUSE=/wheelhouse",
        '--volume "$WHEELHOUSE:/wheelhouse:ro"',
    ):
        assert arg in text
    assert "--require-hashes" in text  # the wheelhouse is downloaded against the lock's hashes too
    # the CMD and the port are the image's (buildah inspect), not a copy of the Dockerfile's
    assert 'config.get("Cmd")' in text and "ExposedPorts" in text
    assert "app.main:app" not in text and "uvicorn" not in text
    assert "/healthz" in text and "/v1/srt" in text and "table16-btrain" in text and "SERVICE_UID=10001" in text
    # the compose file's worker command is started in the image too
    assert " ".join(compose()["services"]["worker"]["command"]) + " --help" in text
    # without its tools it skips, unless CI=true (then it installs them and fails on anything that does not work)
    assert "skipped: " in text and 'in_ci() { [ "${CI:-}" = "true" ]; }' in text and "apt-get install -y" in text
    # docs/deployment.md quotes the size line it prints, with the date it was measured
    assert 'say "image size: $SIZE (buildah images, uncompressed)' in text
    doc = (ROOT / "docs" / "deployment.md").read_text(encoding="utf-8")
    assert "bash scripts/image/check.sh" in doc and "docs/deployment.md" in README
    assert re.search(
        r"On \d{4}-\d\d-\d\d it printed:\n\n```text\nimage check: image size: \d+ MB \(buildah images", doc
    )
    # what it caches stays out of git and out of the build context
    assert ".cache/" in (ROOT / ".gitignore").read_text().splitlines()
    assert ".cache" in (ROOT / ".dockerignore").read_text().splitlines()


def test_the_stand_in_lock_is_the_lock_as_the_running_python_reads_it():
    """scripts/image/standin.py lock: the entries whose markers hold, without the marker, with all their hashes."""
    import importlib.util
    import sys

    from packaging.markers import Marker

    spec = importlib.util.spec_from_file_location("standin", ROOT / "scripts" / "image" / "standin.py")
    standin = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(standin)
    text = (ROOT / "requirements" / "runtime.txt").read_text(encoding="utf-8")
    lines = standin.lock(text)
    names = [line.split("==")[0] for line in lines]
    assert len(names) == len(set(names)) and set(names) <= set(locked("runtime"))
    assert all(";" not in line and " --hash=sha256:" in line for line in lines)
    # async-timeout is locked for python_full_version < '3.11.3' (Debian bookworm's python is 3.11.2)
    old_python = Marker("python_full_version < '3.11.3'").evaluate()
    assert ("async-timeout" in names) == old_python
    assert "numpy" in names and "scipy" in names
    hashes = {name: len(re.findall(r"--hash=", line)) for name, line in zip(names, lines, strict=True)}
    assert hashes["numpy"] > 10  # every file of the version, as in the lock
    tags = standin.tags()
    assert tags[:3] == [
        f"--python-version={sys.version_info[0]}.{sys.version_info[1]}",
        "--implementation=cp",
        f"--abi=cp{sys.version_info[0]}{sys.version_info[1]}",
    ]
    assert any(t.startswith("--platform=") for t in tags)


# ------------------------------------------------------------------------------------------------ compose.yaml
COMPOSE = ROOT / "compose.yaml"
#: schema/compose-spec.json of the Compose Specification (github.com/compose-spec/compose-spec, Apache-2.0), at
#: commit 170098ba07d9f53c383a41bfd4c5166b0a4529a6: what `docker compose config` validates a file against
COMPOSE_SCHEMA = ROOT / "tests" / "api" / "compose-spec.json"
#: the settings compose.yaml takes from the environment (or an .env file), as a user would give them
COMPOSE_ENV = {
    "ROLLOVER_CACHE_SECRET": "0123456789abcdef" * 4,
    "ROLLOVER_API_KEYS": "key-one-0123456789abcdef,key-two-0123456789abcdef",
    "POSTGRES_PASSWORD": "fedcba9876543210",
}


def interpolate(value, env: dict[str, str]):
    """Compose's ${VAR}, ${VAR:-default} and ${VAR:?error} in every string of a parsed compose file."""
    if isinstance(value, dict):
        return {k: interpolate(v, env) for k, v in value.items()}
    if isinstance(value, list):
        return [interpolate(v, env) for v in value]
    if not isinstance(value, str):
        return value

    def one(m: re.Match) -> str:
        name, op, arg = m.group(1), m.group(2), m.group(3)
        if env.get(name):
            return env[name]
        if op == "?":
            raise KeyError(f"{name}: {arg}")
        return arg if op == "-" else ""

    return re.sub(r"\$\{(\w+)(?::([-?])([^}]*))?\}", one, value)


def compose() -> dict:
    import yaml

    return yaml.safe_load(COMPOSE.read_text(encoding="utf-8"))


def test_compose_file_is_valid_against_the_compose_specification():
    """docker compose cannot run here: the file is checked against the specification's own JSON schema."""
    import jsonschema

    schema = json.loads(COMPOSE_SCHEMA.read_text(encoding="utf-8"))
    validator = jsonschema.Draft7Validator(schema)
    errors = [f"{list(e.path)}: {e.message}" for e in validator.iter_errors(compose())]
    assert not errors
    # and it would catch a mistake
    broken = compose()
    broken["services"]["worker"]["replica"] = 2
    assert list(validator.iter_errors(broken))


def test_compose_runs_the_api_its_job_workers_redis_and_postgres_with_the_service_s_own_settings(monkeypatch):
    from urllib.parse import urlsplit

    from app.settings import Settings

    services = compose()["services"]
    assert set(services) == {"api", "worker", "redis", "postgres"}
    known = {f"ROLLOVER_{name.upper()}" for name in Settings.model_fields}
    for name, service in services.items():
        for key in service.get("environment", {}):
            assert not key.startswith("ROLLOVER_") or key in known, (name, key)
    api, worker = services["api"], services["worker"]
    # the same image: the server (its CMD) and the job worker (README "Long batches as jobs")
    assert api["image"] == worker["image"] and api["build"] == worker["build"] == "."
    assert "command" not in api and worker["command"] == ["python", "-m", "app.jobs.worker"]
    assert (ROOT / "app" / "jobs" / "worker.py").is_file()
    assert re.fullmatch(r"\$\{WORKERS:-\d+\}", str(worker["deploy"]["replicas"]))
    # the image's HEALTHCHECK polls the server, which a worker does not run
    assert worker["healthcheck"] == {"disable": True} and "healthcheck" not in api
    # the API publishes the port the image exposes
    exposed = [rest for word, rest in dockerfile_instructions() if word == "EXPOSE"]
    assert [p.rsplit(":", 1)[1] for p in api["ports"]] == exposed
    # the secrets are the user's, required from the environment, never written in the file
    for env in (api["environment"], worker["environment"], services["postgres"]["environment"]):
        for key in ("ROLLOVER_CACHE_SECRET", "ROLLOVER_API_KEYS", "POSTGRES_PASSWORD"):
            assert key not in env or env[key].startswith(f"${{{key}:?"), key
    with pytest.raises(KeyError, match="ROLLOVER_CACHE_SECRET"):
        interpolate(worker["environment"], {})

    api_env, worker_env = interpolate(api["environment"], COMPOSE_ENV), interpolate(worker["environment"], COMPOSE_ENV)
    # the API and the workers share the job store, its queue and the secret that seals it
    for key in ("ROLLOVER_JOBS_BACKEND", "ROLLOVER_REDIS_URL", "ROLLOVER_CACHE_SECRET"):
        assert api_env[key] == worker_env[key], key
    assert api_env["ROLLOVER_JOBS_BACKEND"] == "redis" and api_env["ROLLOVER_CACHE_BACKEND"] == "redis"
    assert urlsplit(api_env["ROLLOVER_REDIS_URL"]).hostname == "redis"
    # the catalog is on (keys) and in the PostgreSQL service, as its user and database
    db = urlsplit(api_env["ROLLOVER_DATABASE_URL"])
    pg = interpolate(services["postgres"]["environment"], COMPOSE_ENV)
    assert db.scheme == "postgresql+psycopg" and db.hostname == "postgres" and db.port == 5432
    assert (db.username, db.password, db.path) == (
        pg["POSTGRES_USER"],
        pg["POSTGRES_PASSWORD"],
        "/" + pg["POSTGRES_DB"],
    )
    assert api_env["ROLLOVER_API_KEYS"] == COMPOSE_ENV["ROLLOVER_API_KEYS"]
    # several server processes in the container: prometheus-client's multiprocess directory on a tmpfs
    assert int(api_env["WEB_CONCURRENCY"]) >= 1 and api_env["PROMETHEUS_MULTIPROC_DIR"] in api["tmpfs"]
    # the service accepts what each container is given
    for env in (api_env, worker_env):
        for key in list(os.environ):
            if key.startswith("ROLLOVER_"):
                monkeypatch.delenv(key)
        for key, value in env.items():
            monkeypatch.setenv(key, value)
        settings = Settings()
        assert settings.jobs_backend == "redis" and settings.cache_secret is not None
    assert Settings().solve_threads == 1  # the worker's: one part on one thread, one worker per core
    # the API and the workers start once Redis (and PostgreSQL) answer
    assert api["depends_on"] == {n: {"condition": "service_healthy"} for n in ("redis", "postgres")}
    assert worker["depends_on"] == {"redis": {"condition": "service_healthy"}}
    assert services["redis"]["healthcheck"]["test"][:2] == ["CMD", "redis-cli"]
    assert services["postgres"]["healthcheck"]["test"][:2] == ["CMD", "pg_isready"]
    # the job store is not evicted to make room, and Redis and PostgreSQL keep their data on volumes
    assert "noeviction" in services["redis"]["command"]
    for name in ("redis", "postgres"):
        assert re.fullmatch(r"(redis|postgres):\d+(\.\d+)?-bookworm", services[name]["image"])
        volume = services[name]["volumes"][0].split(":")[0]
        assert volume in compose()["volumes"]
