"""Run by scripts/image/check.sh with the stand-in base image's own python (in a chroot of its root file system).

    python standin.py lock < requirements/runtime.txt   # the lock as this interpreter reads it
    python standin.py tags                              # pip download options for this interpreter's wheels

``lock`` prints every requirement whose environment marker holds for this interpreter, without the marker and with
all its hashes, so that pip on the host (another Python, whose markers differ: ``python_full_version < '3.11.3'``)
downloads exactly the files this interpreter installs. ``tags`` prints, one a line, the ``--python-version``,
``--implementation``, ``--abi`` and ``--platform`` options that make the host's pip pick the wheels this
interpreter accepts (its manylinux tags follow its glibc). Only the standard library and pip's vendored packaging.
"""

from __future__ import annotations

import re
import sys

from pip._vendor.packaging.markers import Marker
from pip._vendor.packaging.tags import sys_tags


def lock(text: str) -> list[str]:
    lines = [line for line in text.splitlines() if not line.lstrip().startswith("#")]
    joined = re.sub(r"\\\n", " ", "\n".join(lines))
    out = []
    for entry in joined.splitlines():
        entry = entry.strip()
        if not entry:
            continue
        head, sep, hashes = entry.partition(" --hash=")
        requirement, _, marker = head.partition(";")
        if marker.strip() and not Marker(marker.strip()).evaluate():
            continue
        if not sep:
            raise SystemExit(f"no hash for {requirement.strip()!r}: the lock is hashed (scripts/lock.sh)")
        out.append(f"{requirement.strip()} --hash={hashes.strip()}")
    return out


def tags() -> list[str]:
    impl = sys.implementation.name
    if impl != "cpython":
        raise SystemExit(f"the stand-in's python is {impl}, not CPython")
    major, minor = sys.version_info[:2]
    version = f"{major}.{minor}"
    abi = f"cp{major}{minor}"
    platforms: list[str] = []
    for tag in sys_tags():
        if tag.platform != "any" and tag.platform not in platforms:
            platforms.append(tag.platform)
    out = [f"--python-version={version}", "--implementation=cp", f"--abi={abi}"]
    return out + [f"--platform={p}" for p in platforms]


if __name__ == "__main__":
    mode = sys.argv[1] if len(sys.argv) > 1 else ""
    if mode == "lock":
        print("\n".join(lock(sys.stdin.read())))
    elif mode == "tags":
        print("\n".join(tags()))
    else:
        raise SystemExit(__doc__)
