"""The limit of a monotone margin on a bounded range: Brent's method on a bracket that steps off unsolvable ends.

Inverse questions ("the largest payload that still meets 0.35 g") are roots of a margin g(x) = SRT(x) - target
that falls monotonically from a *good* end of a physical range to a *bad* end. Near either end the engine may
have no answer (the body collapses, the SRT leaves the mechanism's range): the margin function returns None
there. :func:`bracketed_limit` then steps off an unsolvable good end, bisects an unsolvable bad end toward the
good one until a solvable point misses the target, and calls Brent's method on the bracket. The outcome is
``found`` (the margin is zero at ``value`` to the tolerance, and never negative: ``value`` meets the target),
``always-met`` (the whole solvable range meets the target:
``value`` is its bad end) or ``never-met`` (``value`` is None). The builder's payload limits and
:func:`engine.road.limits.parameter_limit` (the record's own parameters) both use it.

References
----------
Brent, R. P. (1973), *Algorithms for Minimization without Derivatives*, Ch. 4 (scipy.optimize.brentq).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from scipy.optimize import brentq

from engine.errors import ConvergenceError, InvalidInput

#: the bracket's bad end is bisected toward the good end at most this many times
MAX_BISECTIONS = 60
#: steps of the tolerance back toward the good end that a root on the failing side may take to meet the target
MAX_STEPS_BACK = 8


@dataclass(frozen=True)
class BracketedLimit:
    """Where the margin crosses zero between ``good`` and ``bad``.

    value : the limit (the root, or the bad end of the solvable range when always met); None if never met
    status : ``found``, ``always-met`` or ``never-met``
    margin : the margin at ``value`` (zero up to the tolerance when found, and never below zero)
    evaluations : calls of the margin function
    """

    value: float | None
    status: str
    margin: float | None
    evaluations: int


def bracketed_limit(
    margin: Callable[[float], float | None],
    good: float,
    bad: float,
    *,
    xtol: float,
    field: str = "limit",
) -> BracketedLimit:
    """Limit of a margin that falls monotonically from ``good`` to ``bad`` (Brent's method on a bracket).

    Parameters
    ----------
    margin : g(x), >= 0 where the target is met; None where x cannot be solved [same unit as the target]
    good : the end of the range where the target is most easily met [unit of x]
    bad : the other end [unit of x]
    xtol : absolute tolerance on the limit [unit of x]
    field : the input named when no value in the range can be solved [-]

    Returns
    -------
    BracketedLimit

    Raises
    ------
    InvalidInput : no value between ``good`` and ``bad`` can be solved.
    ConvergenceError : the margin is unsolvable inside a bracket whose ends are solvable.
    """
    calls = 0

    def g(x: float) -> float | None:
        nonlocal calls
        calls += 1
        return margin(x)

    g_good = g(good)
    if g_good is None:  # step off the good end, in growing steps, to the first solvable value
        for k in range(30, 0, -1):
            probe = good + (bad - good) / 2.0**k
            g_probe = g(probe)
            if g_probe is not None:
                good, g_good = probe, g_probe
                break
        else:
            raise InvalidInput(f"no value of {field} in the searched range can be solved", field=field)
    if g_good < 0:
        return BracketedLimit(None, "never-met", None, calls)
    unsolvable = None
    for _ in range(MAX_BISECTIONS):
        g_bad = g(bad)
        if g_bad is None:
            unsolvable = bad
        elif g_bad < 0:
            break
        else:  # solvable and still meets the target: the root lies beyond it
            good, g_good = bad, g_bad
            if unsolvable is None:
                return BracketedLimit(bad, "always-met", g_bad, calls)
        if abs(unsolvable - good) < xtol:  # met up to where the case stops being solvable
            return BracketedLimit(good, "always-met", g_good, calls)
        bad = 0.5 * (good + unsolvable)
    else:
        return BracketedLimit(good, "always-met", g_good, calls)

    def strict(x: float) -> float:
        value = g(x)
        if value is None:
            raise ConvergenceError(f"{field} = {x:.6g} cannot be solved inside a solvable bracket")
        return value

    root = float(brentq(strict, min(good, bad), max(good, bad), xtol=xtol, rtol=1e-12))
    value = strict(root)
    # Brent's root lies within its tolerance of the crossing, on either side; the limit is the largest (smallest)
    # value that *meets* the target, so that a limit's own check passes (0.34999997 g would read "does not meet
    # 0.35 g" at the limit): a root on the failing side steps back toward the good end (the margin is monotone, so
    # a step of the tolerance reaches the met side unless the margin's own rounding hides it there)
    step = xtol if good < bad else -xtol
    for _ in range(MAX_STEPS_BACK):
        if value >= 0.0:
            break
        root -= step
        value = strict(root)
    if value < 0.0:
        raise ConvergenceError(
            f"{field}: no value within {MAX_STEPS_BACK} x {xtol:g} of the root found by Brent's method meets the "
            "target (the margin is not monotone there)"
        )
    return BracketedLimit(root, "found", value, calls)
