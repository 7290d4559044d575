"""Write the app's OpenAPI document to openapi/openapi.json (sorted keys, stable), or check it with --check.

python scripts/export_openapi.py          # rewrite openapi/openapi.json
python scripts/export_openapi.py --check  # exit 1 when the committed file differs from what the app serves
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SPEC_PATH = ROOT / "openapi" / "openapi.json"


def render() -> str:
    sys.path.insert(0, str(ROOT))
    from app.main import create_app

    return json.dumps(create_app().openapi(), indent=2, sort_keys=True, ensure_ascii=False) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="fail when the committed spec has drifted")
    args = parser.parse_args(argv)
    text = render()
    if args.check:
        if not SPEC_PATH.exists() or SPEC_PATH.read_text(encoding="utf-8") != text:
            print(f"{SPEC_PATH.relative_to(ROOT)} is out of date: run scripts/export_openapi.py", file=sys.stderr)
            return 1
        print(f"{SPEC_PATH.relative_to(ROOT)} is up to date")
        return 0
    SPEC_PATH.parent.mkdir(exist_ok=True)
    SPEC_PATH.write_text(text, encoding="utf-8")
    print(f"wrote {SPEC_PATH.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
