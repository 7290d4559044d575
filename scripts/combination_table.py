"""The combination presets' SRTs, as docs/combinations.md shows them, computed by the engine.

    python scripts/combination_table.py           # print the Markdown table
    python scripts/combination_table.py --write   # replace the table between docs/combinations.md's markers

tests/engine/test_combination_presets.py fails when the committed table is not what this prints.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from engine import COMBINATIONS, Case, MissingParameter, get_combination, rollover_threshold  # noqa: E402
from scripts.docblock import write_block  # noqa: E402

DOC = ROOT / "docs" / "combinations.md"
START, END = "<!-- combination-table:start -->", "<!-- combination-table:end -->"


def srt_or_reason(case: Case) -> str:
    try:
        return f"{rollover_threshold(case).srt:.3f}"
    except MissingParameter as exc:  # the 3d model needs the last unit's thesis record
        return "n/a (no thesis record of the last unit)" if "last_unit_record" in str(exc) else f"refused: {exc}"


def render() -> str:
    rows = [
        "| preset | roll-coupled units: SRT [g] (what ended it) | lift-off sequence: unit/group at ay [g] | "
        "governing SRT [g] | rigid [g] | last unit's LLTf/LLTr | 3d model of the last unit with it [g] |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for cid in COMBINATIONS:
        combination = get_combination(cid)
        result = rollover_threshold(Case(combination))
        detail = result.combination
        units = "; ".join(f"{'+'.join(u.units)}: {u.srt:.3f} ({u.limit})" for u in detail.roll_coupled_units)
        lifts = "; ".join(
            f"{e.unit}/{e.group} {e.ay_g:.3f}" for u in detail.roll_coupled_units for e in u.lift_sequence
        )
        rigid = rollover_threshold(Case(combination, model="rigid")).srt
        ratio = detail.last_unit_front_llt_ratio
        three_d = srt_or_reason(Case(combination, model="3d"))
        rows.append(
            f"| `{cid}` | {units} | {lifts} | {result.srt:.3f} | {rigid:.3f} | "
            f"{'n/a' if ratio is None else f'{ratio:.3f}'} | {three_d} |"
        )
    return "\n".join(rows)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="replace the table in docs/combinations.md")
    args = parser.parse_args(argv)
    table = render()
    if not args.write:
        print(table)
        return 0
    write_block(DOC, START, END, table)
    print("docs/combinations.md table updated")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
