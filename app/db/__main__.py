"""Catalog database maintenance.

python -m app.db upgrade            # migrate ROLLOVER_DATABASE_URL to the newest revision
python -m app.db current            # print the revision the database is at and the newest one
python -m app.db upgrade --url postgresql+psycopg://user:pass@host/db
"""

from __future__ import annotations

import argparse
import sys

from . import Database, current_revision, head_revision, upgrade


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m app.db", description=__doc__.splitlines()[0])
    parser.add_argument("command", choices=["upgrade", "current"])
    parser.add_argument("--url", help="database URL (default: ROLLOVER_DATABASE_URL, else sqlite:///./rollover.db)")
    args = parser.parse_args(argv)
    if args.url is None:
        from app.settings import Settings

        args.url = Settings().database_url
    db = Database(args.url)
    try:
        if args.command == "upgrade":
            revision = upgrade(db)
            print(f"{db.safe_url}: at revision {revision} (head {head_revision()})")
        else:
            print(f"{db.safe_url}: at revision {current_revision(db)} (head {head_revision()})")
    finally:
        db.dispose()
    return 0


if __name__ == "__main__":
    sys.exit(main())
