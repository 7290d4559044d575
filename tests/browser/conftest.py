"""Fixtures of the browser tests: one real uvicorn server and one headless chromium for the whole session.

Without chromium and chromedriver the browser tests are skipped on a developer machine and fail under CI
(``CI`` set), where ``.ci/run`` installs them with apt-get (``chromium``, ``chromium-driver``).
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterator
from urllib.parse import urlsplit

import httpx
import pytest

from .harness import LiveServer, find_chromium, start_browser, start_server, wait_until_computed


def pytest_configure(config: pytest.Config) -> None:
    # starlette's TestClient warns that it will move to httpx2 (as in tests/api/conftest.py)
    config.addinivalue_line("filterwarnings", "ignore:Using `httpx` with `starlette.testclient`")


def _binaries() -> tuple[str, str]:
    found = find_chromium()
    if found is None:
        if os.environ.get("CI"):
            pytest.fail("chromium or chromedriver is missing in CI: .ci/run must install chromium and chromium-driver")
        pytest.skip("chromium / chromedriver not found (apt-get install chromium chromium-driver); CI runs these")
    return found


@pytest.fixture(scope="session")
def live_server() -> Iterator[LiveServer]:
    server = start_server()
    try:
        yield server
    finally:
        server.stop()


@pytest.fixture(scope="session")
def api(live_server) -> Iterator[httpx.Client]:
    """A plain HTTP client of the same server (the expected values come from the API, not from the page)."""
    with httpx.Client(base_url=live_server.url, timeout=60) as client:
        yield client


@pytest.fixture(scope="session")
def browser() -> Iterator:
    binaries = _binaries()
    driver = start_browser(binaries)
    try:
        yield driver
    finally:
        driver.quit()


class Page:
    """The calculator page in the session's browser."""

    def __init__(self, driver, server: LiveServer) -> None:
        self.driver = driver
        self.server = server

    def open(self, query: str = "") -> Page:
        self.driver.get(f"{self.server.url}/{query}")
        wait_until_computed(self.driver)
        return self

    def find(self, selector: str):
        from selenium.webdriver.common.by import By

        return self.driver.find_element(By.CSS_SELECTOR, selector)

    def find_all(self, selector: str):
        from selenium.webdriver.common.by import By

        return self.driver.find_elements(By.CSS_SELECTOR, selector)

    def text(self, selector: str) -> str:
        return self.find(selector).text

    def count(self, name: str) -> int:
        return int(self.find("body").get_attribute(f"data-{name}") or 0)

    def run(self, name: str, action, timeout_s: float = 60.0) -> None:
        """Do ``action`` and wait until the page has finished one more run of ``name`` (computations, ...)."""
        from selenium.webdriver.support.ui import WebDriverWait

        before = self.count(name)
        action()
        WebDriverWait(self.driver, timeout_s).until(lambda _: self.count(name) > before)

    def type(self, selector: str, text: str) -> None:
        box = self.find(selector)
        box.clear()
        box.send_keys(text)

    def field_error(self, selector: str) -> str:
        """The messages tied to a control by aria-describedby (where the page shows the API's field errors)."""
        ids = (self.find(selector).get_attribute("aria-describedby") or "").split()
        return " ".join(self.find(f"#{i}").text for i in ids)

    def srt_g(self) -> float:
        """The SRT as the page's text shows it ("0.339 g")."""
        text = self.text("#srt-value")
        assert text.endswith(" g"), text
        return float(text.removesuffix(" g"))

    def network(self) -> tuple[dict[str, str], dict[str, str]]:
        """The requests the page started since the last call (the performance log): request id -> URL, and those
        the browser blocked before sending them: request id -> reason (``csp``, ...)."""
        sent, blocked = {}, {}
        for entry in self.driver.get_log("performance"):
            message = json.loads(entry["message"])["message"]
            params = message.get("params", {})
            if message.get("method") == "Network.requestWillBeSent":
                sent[params["requestId"]] = params["request"]["url"]
            elif message.get("method") == "Network.loadingFailed" and params.get("blockedReason"):
                blocked[params["requestId"]] = params["blockedReason"]
        return sent, blocked

    def console(self) -> list[str]:
        return [e["message"] for e in self.driver.get_log("browser")]

    def hosts(self, urls: list[str]) -> set[str]:
        return {urlsplit(u).netloc for u in urls if urlsplit(u).scheme in ("http", "https", "ws", "wss")}


@pytest.fixture
def page(browser, live_server) -> Page:
    browser.set_window_size(1366, 768)
    p = Page(browser, live_server)
    p.network()  # drain the logs of the previous test
    p.console()
    return p
