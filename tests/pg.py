"""A real PostgreSQL server for the tests: initdb + pg_ctl into a temporary directory, on a free port.

The binaries come from the PATH or /usr/lib/postgresql/<version>/bin (Debian's ``postgresql`` package, which
.ci/run installs). PostgreSQL refuses to run as root: as root the data directory is chowned to the ``postgres``
system user and initdb/pg_ctl run as that user through ``runuser -u postgres --``. The server listens on
127.0.0.1 (trust authentication) and keeps its unix socket in the temporary directory, never in
/var/run/postgresql, so it cannot collide with a system instance.
"""

from __future__ import annotations

import glob
import os
import pwd
import shutil
import socket
import subprocess
import tempfile
import uuid
from pathlib import Path

import pytest


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def postgres_bindir() -> Path | None:
    """The directory of initdb, pg_ctl and postgres (PATH first, then the newest /usr/lib/postgresql/*/bin)."""
    found = shutil.which("postgres"), shutil.which("initdb"), shutil.which("pg_ctl")
    if all(found):
        return Path(os.path.realpath(found[0])).parent
    dirs = sorted(glob.glob("/usr/lib/postgresql/*/bin"), key=lambda d: int(Path(d).parent.name.split(".")[0]))
    for d in reversed(dirs):
        if all((Path(d) / b).is_file() for b in ("postgres", "initdb", "pg_ctl")):
            return Path(d)
    return None


def require_postgres_bindir() -> Path:
    """The binaries' directory; skip when missing locally, fail under CI (``CI`` set), where .ci/run installs them."""
    bindir = postgres_bindir()
    if bindir is None:
        if os.environ.get("CI"):
            pytest.fail("PostgreSQL is missing in CI: .ci/run must install it (apt-get install -y postgresql)")
        pytest.skip("PostgreSQL binaries not found (apt-get install postgresql); CI installs them and runs this")
    if os.geteuid() == 0:
        try:
            pwd.getpwnam("postgres")
        except KeyError:
            if os.environ.get("CI"):
                pytest.fail("running as root without a 'postgres' user to run the server as")
            pytest.skip("running as root without a 'postgres' user to run the server as")
    return bindir


class PostgresServer:
    """initdb + pg_ctl start in a fresh temporary directory; :meth:`stop` removes everything."""

    def __init__(self, bindir: Path) -> None:
        self.bindir = bindir
        self.port = _free_port()
        self.root = Path(tempfile.mkdtemp(prefix="rollover-pg-"))
        self.data = self.root / "data"
        self.log = self.root / "postgres.log"
        self._as_user: list[str] = []
        if os.geteuid() == 0:
            entry = pwd.getpwnam("postgres")
            os.chown(self.root, entry.pw_uid, entry.pw_gid)
            self._as_user = ["runuser", "-u", "postgres", "--"]
        self._run("initdb", "-D", str(self.data), "-U", "postgres", "--auth=trust", "-E", "UTF8", "--no-locale", "-N")
        options = f"-p {self.port} -k {self.root} -c listen_addresses=127.0.0.1"
        self._run("pg_ctl", "-D", str(self.data), "-l", str(self.log), "-o", options, "-w", "-t", "60", "start")
        self.started = True

    def _run(self, binary: str, *args: str) -> None:
        done = subprocess.run(
            [*self._as_user, str(self.bindir / binary), *args], capture_output=True, text=True, timeout=120
        )
        if done.returncode != 0:
            log = self.log.read_text(errors="replace") if self.log.exists() else ""
            raise RuntimeError(f"{binary} failed ({done.returncode}): {done.stderr}\n{done.stdout}\n{log}")

    def url(self, database: str = "postgres") -> str:
        return f"postgresql+psycopg://postgres@127.0.0.1:{self.port}/{database}"

    def create_database(self) -> str:
        """A new empty database; returns its SQLAlchemy URL."""
        import psycopg

        name = "t_" + uuid.uuid4().hex[:16]
        with psycopg.connect(f"host=127.0.0.1 port={self.port} user=postgres dbname=postgres", autocommit=True) as c:
            c.execute(f'CREATE DATABASE "{name}"')
        return self.url(name)

    def stop(self) -> None:
        try:
            if self.started:
                self._run("pg_ctl", "-D", str(self.data), "-m", "fast", "-w", "-t", "60", "stop")
                self.started = False
        finally:
            shutil.rmtree(self.root, ignore_errors=True)
