#!/usr/bin/env bash
# The deployment image built and run, not assumed: buildah builds the Dockerfile on a stand-in for its base image,
# then runs the image's own CMD and checks what it serves (docs/deployment.md). As root:
#
#   bash scripts/image/check.sh          # .ci/run calls it after the test suite, with CI=true
#
# 1. A stand-in for the official python:3.11-slim-bookworm base (which cannot be pulled here), made from Debian's
#    packages: debootstrap --variant=minbase bookworm with python3 and python3-venv, and a virtualenv at /usr/local
#    for the official image's layout (/usr/local/bin/python, /usr/local/bin/python3.11, a pip that is not
#    externally managed, ensurepip's wheels in /usr/local/lib/python3.X/ensurepip/_bundled); imported as a local
#    image.
# 2. The lock's wheels, downloaded by the host's pip (the build's own pip does not trust this machine's certificate
#    setup) for the stand-in's python and platform (scripts/image/standin.py), every file against its sha256.
# 3. buildah bud of the Dockerfile as it is, given --build-arg BASE_IMAGE=<the stand-in> and the wheelhouse
#    (--build-arg WHEELHOUSE=/wheelhouse, mounted read-only; the build still installs --require-hashes).
# 4. The image's own CMD (read from the image) started in a container, then: GET /healthz and POST /v1/srt answer
#    200 (the Table 16 B-train's SRT, 0.339 g), the server runs as uid 10001, there is no pip in the image, the job
#    worker's entry point starts, the server stops on SIGTERM; and the image's size is printed. Everything it made
#    (containers, images) is removed at the end, pass or fail.
#
# Where buildah or debootstrap is missing (or not root) it prints "skipped: ..." and exits 0, unless CI=true: then
# it installs them with apt-get and fails loudly on anything that does not work. The stand-in's root file system and
# the wheelhouse are cached in .cache/image/ (gitignored; IMAGE_CHECK_CACHE moves it) so that local re-runs are
# quick; a clean clone (CI) builds them anew. DEBIAN_MIRROR overrides the mirror read from the host's apt sources.
set -euo pipefail
cd "$(dirname "$0")/../.."
ROOT=$PWD
START=$SECONDS
export PATH="$PATH:/usr/sbin:/sbin"

SUITE=bookworm
# what the official slim image has besides python (ca-certificates, netbase, tzdata) and what the layout needs
STANDIN_PACKAGES=python3,python3-venv,ca-certificates,netbase,tzdata
SERVICE_UID=10001
EXPECTED_SRT=0.339  # POST /v1/srt {"vehicle": "table16-btrain"}: docs/examples.md (0.33910720747232653)
CACHE=${IMAGE_CHECK_CACHE:-$ROOT/.cache/image}

say() { printf 'image check: %s\n' "$*"; }
fail() { printf 'image check: FAILED: %s\n' "$*" >&2; exit 1; }
in_ci() { [ "${CI:-}" = "true" ]; }
skip() {
    if in_ci; then fail "$1"; fi
    printf 'skipped: image check: %s (CI=true installs what is missing and fails instead)\n' "$1"
    exit 0
}
# a directory removed without crossing into anything mounted beneath it (a debootstrap stopped half-way leaves
# its target's /proc and /sys mounted)
safe_rm() {
    local dir
    for dir in "$@"; do
        [ -e "$dir" ] || continue
        findmnt -rn -o TARGET | { grep -F "$(realpath "$dir")/" || true; } | sort -r | xargs -r -n 1 umount -l
        rm -rf --one-file-system "$dir"
    done
}

# ------------------------------------------------------------------------------------------------ the tools
if [ "$(id -u)" -ne 0 ]; then
    skip "needs root (debootstrap, chroot and buildah's image store)"
fi
MISSING=()
command -v buildah >/dev/null 2>&1 || MISSING+=(buildah)
command -v debootstrap >/dev/null 2>&1 || MISSING+=(debootstrap)
[ -f /usr/share/keyrings/debian-archive-keyring.gpg ] || MISSING+=(debian-archive-keyring)
command -v ss >/dev/null 2>&1 || MISSING+=(iproute2)
command -v python3 >/dev/null 2>&1 || MISSING+=(python3)
if [ "${#MISSING[@]}" -gt 0 ]; then
    in_ci || skip "missing ${MISSING[*]}"
    say "installing ${MISSING[*]}"
    apt-get update
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${MISSING[@]}"
fi
python3 -m pip --version >/dev/null 2>&1 || skip "the host's python3 has no pip (it downloads the wheelhouse)"

# ------------------------------------------------------------------------------------------- clean-up on exit
RUN_ID="rollover-image-check-$$"
STANDIN_IMAGE="localhost/$RUN_ID-base:$SUITE"
IMAGE="localhost/$RUN_ID:latest"
TMP=$(mktemp -d)
CONTAINERS=()
IMAGES=()
SERVER_PIDS=()
cleanup() {
    local rc=$?
    set +e
    # the server first (SIGTERM: it shuts down), then buildah run if it has not ended with it
    for pid in "${SERVER_PIDS[@]}"; do
        kill "$pid" 2>/dev/null
        for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        kill -KILL "$pid" 2>/dev/null
    done
    wait 2>/dev/null
    for ctr in "${CONTAINERS[@]}"; do buildah rm "$ctr" >/dev/null 2>&1; done
    for image in "${IMAGES[@]}"; do buildah rmi "$image" >/dev/null 2>&1; done
    rm -rf "$TMP"
    if [ "$rc" -ne 0 ]; then say "failed after $((SECONDS - START)) s (containers and images removed)" >&2; fi
}
trap cleanup EXIT

# ------------------------------------------------------------------------------ 1. the stand-in base image
ARCH=$(dpkg --print-architecture)
debian_mirror() {
    # the host's own Debian mirror, from its apt sources (deb822 .sources or one-line .list): the stanza for the
    # suite if there is one, else the first plain Debian one (not security, not updates)
    python3 - "$SUITE" <<'EOF'
import glob, re, sys
suite = sys.argv[1]
found = []  # (uri, suites)
for path in sorted(glob.glob("/etc/apt/sources.list.d/*.sources")):
    for stanza in open(path, encoding="utf-8").read().split("\n\n"):
        fields = {}
        for line in stanza.splitlines():
            if line.strip() and not line.lstrip().startswith("#") and ":" in line and not line[0].isspace():
                key, value = line.split(":", 1)
                fields[key.strip().lower()] = value.strip()
        if "deb" in fields.get("types", "").split() and fields.get("enabled", "yes").lower() != "no":
            for uri in fields.get("uris", "").split():
                found.append((uri, fields.get("suites", "").split()))
for path in ["/etc/apt/sources.list", *sorted(glob.glob("/etc/apt/sources.list.d/*.list"))]:
    try:
        lines = open(path, encoding="utf-8").read().splitlines()
    except OSError:
        continue
    for line in lines:
        words = re.sub(r"\[[^]]*\]", " ", line.split("#", 1)[0]).split()  # without its [options]
        if len(words) >= 3 and words[0] == "deb":
            found.append((words[1], [words[2]]))
for uri, suites in found:
    if suite in suites:
        print(uri.rstrip("/")); raise SystemExit
for uri, suites in found:
    if uri.rstrip("/").endswith("/debian") and not any("-" in s for s in suites):
        print(uri.rstrip("/")); raise SystemExit
EOF
}

# the cached root file system is made again when this script (its recipe) or the architecture changes
STANDIN_KEY=$(cat scripts/image/check.sh - <<<"$ARCH" | sha256sum | cut -c1-16)
STANDIN_TAR="$CACHE/standin-$SUITE-$ARCH-$STANDIN_KEY.tar"
mkdir -p "$CACHE"
if [ -f "$STANDIN_TAR" ]; then
    say "stand-in base: cached $STANDIN_TAR"
else
    MIRROR=${DEBIAN_MIRROR:-$(debian_mirror)}
    [ -n "$MIRROR" ] || fail "no Debian mirror in the host's apt sources: set DEBIAN_MIRROR"
    say "stand-in base: debootstrap --variant=minbase $SUITE ($STANDIN_PACKAGES), about a minute"
    safe_rm "$CACHE"/standin-*  # older recipes, a stopped run's leftovers
    WORK=$(mktemp -d "$CACHE/standin-work.XXXXXX")
    ROOTFS="$WORK/rootfs"
    if ! debootstrap --variant=minbase --include="$STANDIN_PACKAGES" "$SUITE" "$ROOTFS" "$MIRROR" \
            >"$WORK/debootstrap.log" 2>&1; then
        tail -n 40 "$WORK/debootstrap.log" >&2
        fail "debootstrap $SUITE from the host's mirror"
    fi
    # the official image's layout: its python is /usr/local/bin/python3.X with a pip of its own, not externally
    # managed; here a virtualenv at /usr/local on Debian's /usr/bin/python3 gives the same paths
    chroot "$ROOTFS" /usr/bin/python3 -m venv /usr/local
    rm -f "$ROOTFS"/usr/local/bin/{activate,activate.csh,activate.fish,Activate.ps1}
    PYVER=$(chroot "$ROOTFS" /usr/local/bin/python -c 'import sys; print("%d.%d" % sys.version_info[:2])')
    [ -x "$ROOTFS/usr/local/bin/python" ] && [ -e "$ROOTFS/usr/local/bin/python$PYVER" ] \
        || fail "the stand-in has no /usr/local/bin/python$PYVER"
    chroot "$ROOTFS" /usr/local/bin/python -m pip --version >/dev/null
    # ensurepip's bundled wheels are where the official image keeps them (the Dockerfile deletes them there);
    # Debian's copies in /usr/share/python-wheels would otherwise be a pip the official image does not have
    BUNDLED="$ROOTFS/usr/local/lib/python$PYVER/ensurepip/_bundled"
    mkdir -p "$BUNDLED"
    mv "$ROOTFS"/usr/share/python-wheels/*.whl "$BUNDLED/"
    # as the official image: no package lists or downloaded packages; /dev, /proc and /sys are the runtime's
    rm -rf "$ROOTFS"/var/cache/apt/archives/*.deb "$ROOTFS"/var/cache/apt/*.bin "$ROOTFS"/var/lib/apt/lists/*
    tar --numeric-owner -C "$ROOTFS" --exclude='./dev/*' --exclude='./proc/*' --exclude='./sys/*' \
        -cf "$WORK/rootfs.tar" .
    mv "$WORK/rootfs.tar" "$STANDIN_TAR"
    safe_rm "$WORK"
fi

# import it: a scratch container, the root file system unpacked into it, committed as a local image
CTR=$(buildah from scratch)
CONTAINERS+=("$CTR")
MNT=$(buildah mount "$CTR")
tar --numeric-owner -xpf "$STANDIN_TAR" -C "$MNT"
PYVER=$(chroot "$MNT" /usr/local/bin/python -c 'import sys; print("%d.%d.%d" % sys.version_info[:3])')
# the lock as the stand-in's python reads it, and the wheel tags it accepts (scripts/image/standin.py)
chroot "$MNT" /usr/local/bin/python -I -c "$(cat scripts/image/standin.py)" lock \
    <requirements/runtime.txt >"$TMP/runtime-standin.txt"
chroot "$MNT" /usr/local/bin/python -I -c "$(cat scripts/image/standin.py)" tags >"$TMP/tags.txt"
buildah umount "$CTR" >/dev/null
buildah config --env PATH=/usr/local/bin:/usr/local/sbin:/usr/sbin:/usr/bin:/sbin:/bin --env LANG=C.UTF-8 \
    --env PYTHON_VERSION="$PYVER" --cmd '["python3"]' \
    --label org.opencontainers.image.description="rollover image check: stand-in for python:$PYVER-slim-$SUITE" "$CTR"
buildah commit --quiet --rm "$CTR" "$STANDIN_IMAGE" >/dev/null
CONTAINERS=()
IMAGES+=("$STANDIN_IMAGE")
say "stand-in base: $STANDIN_IMAGE (Debian $SUITE, python $PYVER at /usr/local/bin/python)"

# ------------------------------------------------------------------------------------------ 2. the wheelhouse
mapfile -t TAGS <"$TMP/tags.txt"
WHEELS_KEY=$(cat "$TMP/runtime-standin.txt" "$TMP/tags.txt" pyproject.toml | sha256sum | cut -c1-16)
WHEELHOUSE="$CACHE/wheelhouse-$WHEELS_KEY"
find "$CACHE" -maxdepth 1 -name 'wheelhouse-*' ! -name "wheelhouse-$WHEELS_KEY" -exec rm -rf {} +
mkdir -p "$WHEELHOUSE"
say "wheelhouse: $(grep -c '==' "$TMP/runtime-standin.txt") locked packages for python $PYVER ($WHEELHOUSE)"
python3 -m pip download -qq --disable-pip-version-check --require-hashes --only-binary=:all: "${TAGS[@]}" \
    -r "$TMP/runtime-standin.txt" -d "$WHEELHOUSE" \
    || fail "pip download of requirements/runtime.txt for the stand-in's python"
# and what pyproject.toml's build-system requires (setuptools): pip builds the project with it in the build stage
REQUIRES=$(python3 -c 'import tomllib
print("\n".join(tomllib.load(open("pyproject.toml", "rb"))["build-system"]["requires"]))')
mapfile -t BUILD_REQUIRES <<<"$REQUIRES"
python3 -m pip download -qq --disable-pip-version-check --only-binary=:all: "${TAGS[@]}" \
    "${BUILD_REQUIRES[@]}" -d "$WHEELHOUSE" || fail "pip download of ${BUILD_REQUIRES[*]}"

# ------------------------------------------------------------------------------------------- 3. the build
say "buildah bud --build-arg BASE_IMAGE=$STANDIN_IMAGE (log: .cache/image/build.log)"
BUILD_START=$SECONDS
if ! buildah bud --isolation chroot --network host --format docker --pull=never \
        --build-arg BASE_IMAGE="$STANDIN_IMAGE" --build-arg WHEELHOUSE=/wheelhouse \
        --volume "$WHEELHOUSE:/wheelhouse:ro" --iidfile "$TMP/iid" --tag "$IMAGE" --file Dockerfile . \
        >"$CACHE/build.log" 2>&1; then
    tail -n 60 "$CACHE/build.log" >&2
    fail "buildah bud of the Dockerfile"
fi
IMAGES=("$IMAGE" "${IMAGES[@]}")
say "built $IMAGE in $((SECONDS - BUILD_START)) s: $(grep -c ' STEP [0-9]*/' "$CACHE/build.log") steps"

# ----------------------------------------------------------------------------------------------- 4. run it
buildah inspect --type image "$IMAGE" >"$TMP/inspect.json"
config() {  # a field of the image's configuration (buildah inspect), as lines of text
    python3 - "$TMP/inspect.json" "$1" <<'EOF'
import json, sys
image = json.load(open(sys.argv[1]))
config, docker = image["OCIv1"]["config"], image["Docker"]["config"]
field = sys.argv[2]
if field == "cmd":  # exec form: an argv, one argument a line
    argv = config.get("Cmd")
    assert isinstance(argv, list) and argv and all("\n" not in a for a in argv), argv
    print("\n".join(argv))
elif field == "port":  # the one TCP port it exposes
    ports = [p.split("/")[0] for p in config.get("ExposedPorts") or {} if p.endswith("/tcp")]
    assert len(ports) == 1, ports
    print(ports[0])
elif field == "user":
    print(config.get("User") or "root")
elif field == "healthcheck":  # kept by --format docker
    print(" ".join((docker.get("Healthcheck") or {}).get("Test") or []))
EOF
}
CMD_LINES=$(config cmd) || fail "the image's CMD is not an exec-form argv"
mapfile -t CMD <<<"$CMD_LINES"
PORT=$(config port) || fail "the image exposes no single TCP port"
[ -n "$(config healthcheck)" ] || fail "the image has no HEALTHCHECK (built with --format docker)"
if ss -Hltn "sport = :$PORT" | grep -q .; then fail "port $PORT is already in use on this machine"; fi

RUN_CTR=$(buildah from --pull=never "$IMAGE")
CONTAINERS+=("$RUN_CTR")
say "running the image's CMD as its user $(config user): ${CMD[*]}"
buildah run --isolation chroot --network host "$RUN_CTR" -- "${CMD[@]}" >"$CACHE/server.log" 2>&1 &
RUN_PID=$!
SERVER_PIDS+=("$RUN_PID")

server_failed() {
    tail -n 40 "$CACHE/server.log" >&2
    fail "$1"
}
# wait until it listens (its imports take a few seconds), or it exits
for _ in $(seq 600); do
    kill -0 "$RUN_PID" 2>/dev/null || server_failed "the image's CMD exited before it listened on $PORT"
    ss -Hltn "sport = :$PORT" | grep -q . && break
    sleep 0.1
done
SERVER_PID=$(ss -Hltnp "sport = :$PORT" | grep -o 'pid=[0-9]*' | head -n 1 | cut -d= -f2)
[ -n "$SERVER_PID" ] || server_failed "nothing listens on $PORT after 60 s"
# it is the process buildah run started (a descendant of it), not something else on the port
pid=$SERVER_PID
while [ "$pid" -gt 1 ] && [ "$pid" != "$RUN_PID" ]; do pid=$(awk '/^PPid:/ {print $2}' "/proc/$pid/status"); done
[ "$pid" = "$RUN_PID" ] || fail "the process on port $PORT ($SERVER_PID) is not the image's"
SERVER_PIDS=("$SERVER_PID" "${SERVER_PIDS[@]}")

python3 - "$PORT" "$EXPECTED_SRT" <<'EOF' || server_failed "the service's answers"
import json, sys, time, urllib.request
port, expected = sys.argv[1], float(sys.argv[2])
base = f"http://127.0.0.1:{port}"

def call(method, path, body=None):
    data = None if body is None else json.dumps(body).encode()
    req = urllib.request.Request(base + path, data=data, method=method, headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(req, timeout=30) as r:
        return r.status, json.loads(r.read())

for _ in range(100):  # listening is not yet serving: the lifespan may still be starting
    try:
        status, health = call("GET", "/healthz")
        break
    except OSError:
        time.sleep(0.1)
else:
    raise SystemExit("GET /healthz never answered")
assert status == 200 and health["status"] == "ok", (status, health)
print(f"image check: GET /healthz -> {status} {json.dumps(health)}")
status, srt = call("POST", "/v1/srt", {"vehicle": "table16-btrain"})
assert status == 200 and abs(srt["srt"] - expected) < 0.0005, (status, srt.get("srt"))
print(f"image check: POST /v1/srt table16-btrain -> {status}, srt {srt['srt']:.4f} g (expected {expected})")
EOF

UIDS=$(awk '/^Uid:/ {print $2, $3, $4, $5}' "/proc/$SERVER_PID/status")
[ "$UIDS" = "$SERVICE_UID $SERVICE_UID $SERVICE_UID $SERVICE_UID" ] \
    || fail "the server (pid $SERVER_PID) runs as uid $UIDS, not $SERVICE_UID"
say "the server (pid $SERVER_PID) runs as uid $SERVICE_UID (real, effective, saved, filesystem)"

# no installer anywhere in the image: no pip module, script, wheel or dist-info, for any of its pythons
MNT=$(buildah mount "$RUN_CTR")
find "$MNT" -xdev \( -name pip -o -name 'pip[0-9]*' -o -name 'pip-*' \) >"$TMP/pip.txt"
buildah umount "$RUN_CTR" >/dev/null
[ ! -s "$TMP/pip.txt" ] || fail "pip in the image: $(sed "s|^$MNT||" "$TMP/pip.txt" | tr '\n' ' ')"
for python in python /usr/local/bin/python /usr/bin/python3; do
    buildah run --isolation chroot --network host "$RUN_CTR" -- "$python" -c \
        'import importlib.util, sys; sys.exit(importlib.util.find_spec("pip") is not None)' \
        || fail "$python in the image imports pip"
done
say "no pip in the image (no file named pip*, and python, /usr/local/bin/python, /usr/bin/python3 cannot import it)"

# the job worker's entry point (compose.yaml's worker command) is in the image too and starts
buildah run --isolation chroot --network host "$RUN_CTR" -- python -m app.jobs.worker --help >"$TMP/worker.txt" 2>&1 \
    || { cat "$TMP/worker.txt" >&2; fail "python -m app.jobs.worker --help in the image"; }
say "python -m app.jobs.worker --help runs in the image (the compose file's worker command)"

# it stops when asked (docker stop: SIGTERM, then SIGKILL after 10 s)
kill "$SERVER_PID"
for _ in $(seq 100); do kill -0 "$RUN_PID" 2>/dev/null || break; sleep 0.1; done
if kill -0 "$RUN_PID" 2>/dev/null; then server_failed "the server was still running 10 s after SIGTERM"; fi
SERVER_PIDS=()
say "the server stopped on SIGTERM"

# ------------------------------------------------------------------------------------------------ its size
size_of() { buildah images --format '{{.Size}}' "$1" | head -n 1; }
SIZE=$(size_of "$IMAGE")
BASE_SIZE=$(size_of "$STANDIN_IMAGE")
ADDED=$(python3 - "$SIZE" "$BASE_SIZE" <<'EOF'
import re, sys
units = {"B": 1, "KB": 1e3, "kB": 1e3, "MB": 1e6, "GB": 1e9}  # buildah prints decimal units
image, base = (float(m[1]) * units[m[2]] for m in (re.fullmatch(r"([\d.]+)\s*(\w+)", s.strip()) for s in sys.argv[1:]))
print(f"{(image - base) / 1e6:.0f} MB")
EOF
)
say "image size: $SIZE (buildah images, uncompressed): the stand-in base $BASE_SIZE + the Dockerfile's layers $ADDED"
say "passed in $((SECONDS - START)) s"
