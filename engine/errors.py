"""Exception hierarchy of the rollover engine.

Modelled on python-control: small classes that subclass the built-in they refine, so callers can catch
either the specific class or the built-in. The HTTP layer maps each class to a problem type (RFC 9457).

- :class:`InvalidVehicle` / :class:`InvalidRoad` / :class:`InvalidLoad` (``ValueError``): the inputs are
  physically impossible or outside the model's domain; raised before any solving. ``field`` names the
  offending input (the record's field name) so the HTTP layer can point at it.
- :class:`MissingParameter` (``InvalidVehicle``): a model needs a field the record leaves null.
- :class:`UnknownPreset` (``KeyError``): no preset with that id.
- :class:`MechanismSingular` (``ArithmeticError``): the Davies statics are inconsistent, or a quantity the
  caller asked for is not determined by the equations (it has a component in the null space).
- :class:`ConvergenceError` (``ArithmeticError``): the geometry/force iteration or the threshold search did
  not converge (typically the vehicle is at or beyond its static stability limit).
"""

from __future__ import annotations


class RolloverError(Exception):
    """Base class of every error the engine raises on purpose."""


class InvalidInput(RolloverError, ValueError):
    """An input is outside the model's domain. ``field`` names it (dotted path), ``value`` echoes it."""

    def __init__(self, message: str, *, field: str | None = None, value: object = None) -> None:
        super().__init__(message)
        self.field = field
        self.value = value


class InvalidVehicle(InvalidInput):
    """The vehicle record is physically impossible or inconsistent."""


class MissingParameter(InvalidVehicle):
    """A model needs a vehicle field that the record leaves null."""


class InvalidRoad(InvalidInput):
    """The road geometry (bank, slope, trailer angle, radius, speed) is outside the model's domain."""


class InvalidLoad(InvalidInput):
    """The load case (CG offsets, overweight, lateral-load-transfer limit) is impossible."""


class UnknownPreset(RolloverError, KeyError):
    """No preset vehicle has this id."""

    def __init__(self, preset_id: str, known: list[str]) -> None:
        super().__init__(preset_id)
        self.preset_id = preset_id
        self.known = known

    def __str__(self) -> str:  # KeyError quotes its argument; give a sentence instead
        return f"unknown vehicle preset {self.preset_id!r}; known presets: {', '.join(self.known)}"


class MechanismSingular(RolloverError, ArithmeticError):
    """The statics of the mechanism are inconsistent or do not determine a requested quantity."""


class ConvergenceError(RolloverError, ArithmeticError):
    """An iteration did not converge; ``iterations`` and ``residual`` say how far it got."""

    def __init__(self, message: str, *, iterations: int | None = None, residual: float | None = None) -> None:
        super().__init__(message)
        self.iterations = iterations
        self.residual = residual
