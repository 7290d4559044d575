"""A real uvicorn server and Debian's headless chromium (Selenium + chromium-driver), for the browser tests and
``scripts/screenshots.py``.

The server is a separate ``uvicorn app.main:app`` process on a free port with the embedded defaults: the
in-process cache and a SQLite catalog in a temporary directory (one bearer key, so saved vehicles can be used).
The browser is started with the system ``chromium`` and ``chromedriver`` given explicitly (Selenium Manager never
downloads anything) and with its performance and console logs on, so tests can list every request the page made.
"""

from __future__ import annotations

import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
#: the bearer key of the test server's catalog (at least 16 characters)
TEST_KEY = "page-test-key-0123456789"
CHROMIUM_NAMES = ("chromium", "chromium-browser")
DRIVER_NAMES = ("chromedriver", "chromium-driver")


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def find_chromium() -> tuple[str, str] | None:
    """The system chromium and chromedriver binaries (Debian: apt-get install chromium chromium-driver), or None."""
    browser = next((p for p in map(shutil.which, CHROMIUM_NAMES) if p), None)
    driver = next((p for p in map(shutil.which, DRIVER_NAMES) if p), None)
    if driver is None and Path("/usr/lib/chromium/chromedriver").exists():
        driver = "/usr/lib/chromium/chromedriver"
    return (browser, driver) if browser and driver else None


@dataclass
class LiveServer:
    url: str
    key: str
    proc: subprocess.Popen
    workdir: tempfile.TemporaryDirectory

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.workdir.cleanup()


def start_server(timeout_s: float = 90.0) -> LiveServer:
    """``uvicorn app.main:app`` on a free port of 127.0.0.1; returns once ``/healthz`` answers."""
    workdir = tempfile.TemporaryDirectory(prefix="rollover-page-")
    port = free_port()
    env = {
        **os.environ,
        "ROLLOVER_CACHE_BACKEND": "memory",
        "ROLLOVER_DATABASE_URL": f"sqlite:///{Path(workdir.name) / 'rollover.db'}",
        "ROLLOVER_API_KEYS": TEST_KEY,
        "ROLLOVER_LOG_LEVEL": "WARNING",
    }
    log = open(Path(workdir.name) / "uvicorn.log", "wb")  # noqa: SIM115 (closed with the directory)
    proc = subprocess.Popen(
        [sys.executable, "-m", "uvicorn", "app.main:app", "--host", "127.0.0.1", "--port", str(port)],
        cwd=ROOT,
        env=env,
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    server = LiveServer(f"http://127.0.0.1:{port}", TEST_KEY, proc, workdir)
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            text = (Path(workdir.name) / "uvicorn.log").read_text(errors="replace")
            server.stop()
            raise RuntimeError(f"uvicorn exited with {proc.returncode}:\n{text[-3000:]}")
        try:
            with urllib.request.urlopen(f"{server.url}/healthz", timeout=1) as r:
                if r.status == 200:
                    return server
        except OSError:
            time.sleep(0.2)
    server.stop()
    raise RuntimeError(f"uvicorn did not answer on port {port} within {timeout_s:g} s")


def start_browser(binaries: tuple[str, str], width: int = 1366, height: int = 768):
    """Headless chromium through chromedriver, with the performance (network) and browser (console) logs."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    browser, driver = binaries
    options = webdriver.ChromeOptions()
    options.binary_location = browser
    for arg in (
        "--headless=new",
        "--no-sandbox",  # root in containers
        "--disable-dev-shm-usage",
        f"--window-size={width},{height}",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-default-apps",
        "--disable-sync",
        "--lang=en-US",
    ):
        options.add_argument(arg)
    options.set_capability("goog:loggingPrefs", {"performance": "ALL", "browser": "ALL"})
    return webdriver.Chrome(service=Service(driver), options=options)


def wait_until_computed(driver, timeout_s: float = 60.0) -> None:
    """Wait for the page's start-up (and the computation a link asks for) to finish."""
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    WebDriverWait(driver, timeout_s).until(
        lambda d: d.find_element(By.TAG_NAME, "body").get_attribute("data-computed") == "true"
    )
