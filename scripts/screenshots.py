"""Screenshots of the calculator page for the README: docs/screenshots/calculator-desktop.png (1366 x 900) and
calculator-phone.png (390 x 844), taken with Debian's headless chromium against a fresh local server.

    python scripts/screenshots.py            # writes both files
    python scripts/screenshots.py --out DIR  # somewhere else

Needs chromium and chromedriver (apt-get install chromium chromium-driver) and the test extra (selenium).
"""

from __future__ import annotations

import argparse
import base64
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.browser.harness import find_chromium, start_browser, start_server, wait_until_computed  # noqa: E402

#: the case shown: the B-double combination (tractor, lead trailer, Table 16's rear trailer) on a 4 % bank, with a
#: curve speed and the road design for 8 %
QUERY = "?vehicle=btrain-table16&bank_percent=4&radius_m=120"


def capture(driver, path: Path) -> None:
    shot = driver.execute_cdp_cmd("Page.captureScreenshot", {"format": "png"})
    path.write_bytes(base64.b64decode(shot["data"]))
    print(f"wrote {path.relative_to(ROOT) if path.is_relative_to(ROOT) else path}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "screenshots")
    args = parser.parse_args()
    binaries = find_chromium()
    if binaries is None:
        print("chromium and chromedriver are needed: apt-get install chromium chromium-driver", file=sys.stderr)
        return 1
    args.out.mkdir(parents=True, exist_ok=True)
    server = start_server()
    driver = start_browser(binaries)
    try:
        for name, width, height, mobile in (("desktop", 1366, 900, False), ("phone", 390, 844, True)):
            driver.execute_cdp_cmd(
                "Emulation.setDeviceMetricsOverride",
                {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": mobile},
            )
            driver.get(f"{server.url}/{QUERY}")
            wait_until_computed(driver)
            if mobile:  # on a phone the result follows the inputs: one tap on the bar's link shows it
                driver.execute_script("document.getElementById('jump-result').click()")
            capture(driver, args.out / f"calculator-{name}.png")
    finally:
        driver.quit()
        server.stop()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
