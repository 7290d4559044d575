"""Payload CGs: deck loads (uniform, mixed freight, sloping decks), liquid tanks, and the tare."""

from __future__ import annotations

import math
from collections.abc import Sequence

from scipy.optimize import brentq

from engine.builder.spec import (
    LOAD_DISTRIBUTIONS,
    TANK_SHAPES,
    DeckSpec,
    MassItem,
    PayloadSpec,
    TankSpec,
    TareSpec,
    check_choice,
    check_number,
)
from engine.errors import InvalidVehicle

# ------------------------------------------------------------------------------------------ payload CGs


def _segment_centroid_height(depth_m: float, radius_m: float) -> float:
    """Centroid height above the bottom of a circle's segment of depth ``depth_m`` [m].

    Central angle theta = 2 acos((R - d)/R); centroid 4 R sin^3(theta/2) / (3 (theta - sin theta)) below the
    centre [3].
    """
    theta = 2.0 * math.acos(max(-1.0, min(1.0, (radius_m - depth_m) / radius_m)))
    below_centre = 4.0 * radius_m * math.sin(theta / 2.0) ** 3 / (3.0 * (theta - math.sin(theta)))  # [3]
    return radius_m - below_centre


def _segment_area_fraction(depth_m: float, radius_m: float) -> float:
    """Area of a circle's segment of depth ``depth_m`` over the circle's area, (theta - sin theta) / 2 pi [-]."""
    theta = 2.0 * math.acos(max(-1.0, min(1.0, (radius_m - depth_m) / radius_m)))
    return (theta - math.sin(theta)) / (2.0 * math.pi)


def tank_liquid_cg_height_m(
    height_m: float, bottom_height_m: float, *, fill_height_m: float | None = None, fill_fraction: float | None = None
) -> float:
    """CG height above the ground of a liquid in a circular or elliptical tank [m].

    An ellipse is a circle of radius height/2 stretched horizontally; the stretch keeps heights and area ratios,
    so the liquid segment's centroid height is the circle's whatever the tank's width.

    Parameters
    ----------
    height_m : inside height of the tank (diameter of a circular one) [m]
    bottom_height_m : inside bottom of the tank above the ground [m]
    fill_height_m : liquid depth [m] (give this or ``fill_fraction``)
    fill_fraction : liquid volume over tank volume [-]

    References
    ----------
    Centroid of a circular segment, 4 R sin^3(theta/2) / (3 (theta - sin theta)) below the centre (sector minus
    triangle, see the module's reference [3]).
    """
    r = height_m / 2.0
    if fill_height_m is None:
        if fill_fraction >= 1.0:
            return bottom_height_m + r
        fill_height_m = brentq(lambda d: _segment_area_fraction(d, r) - fill_fraction, 0.0, height_m, xtol=1e-12)
    return bottom_height_m + _segment_centroid_height(fill_height_m, r)


def _simpson(f0: float, fm: float, f1: float, length: float) -> float:
    """Simpson's rule on one interval: exact for the polynomials of degree <= 3 integrated here."""
    return length * (f0 + 4.0 * fm + f1) / 6.0


def sloped_load_centroid(
    length_m: float,
    deck_front_m: float,
    deck_rear_m: float,
    top_front_m: float,
    top_rear_m: float,
    cg_fraction: float = 0.5,
) -> tuple[float, float]:
    """Centroid (distance behind the load's front end, height above the ground) of a load on a sloping deck [m].

    Deck d(s) and load top t(s) vary linearly over the load's length; the thickness h = t - d carries the mass,
    whose CG in each section is at d + f h (f = 0.5 uniform, 0.4 mixed freight). Hence
    s_bar = int s h ds / int h ds and z_bar = int (d + f h) h ds / int h ds; the integrands are quadratic, so
    Simpson's rule is exact.

    Parameters
    ----------
    length_m : length of the load [m]
    deck_front_m, deck_rear_m : deck height above the ground at the load's front and rear [m]
    top_front_m, top_rear_m : top of the load above the ground at its front and rear [m]
    cg_fraction : section CG height above the deck as a fraction of the thickness [-]
    """
    deck_mid, top_mid = (deck_front_m + deck_rear_m) / 2.0, (top_front_m + top_rear_m) / 2.0
    h0, hm, h1 = top_front_m - deck_front_m, top_mid - deck_mid, top_rear_m - deck_rear_m
    area = _simpson(h0, hm, h1, length_m)
    s_bar = _simpson(0.0, length_m / 2.0 * hm, length_m * h1, length_m) / area
    z_bar = (
        _simpson(
            (deck_front_m + cg_fraction * h0) * h0,
            (deck_mid + cg_fraction * hm) * hm,
            (deck_rear_m + cg_fraction * h1) * h1,
            length_m,
        )
        / area
    )
    return s_bar, z_bar


def _payload_extent(p: PayloadSpec, deck: DeckSpec | None, path: str) -> tuple[float, float, str]:
    """Front end and length of a payload [m], with how they were obtained."""
    if p.length_m is not None:
        length = check_number(p.length_m, f"{path}.length_m")
    elif deck is not None:
        length = deck.length_m
    else:
        raise InvalidVehicle(
            f"{path} has no longitudinal position: give {path}.cg_from_kingpin_m, or front_from_kingpin_m and "
            "length_m, or the vehicle's deck",
            field=f"{path}.cg_from_kingpin_m",
        )
    if p.front_from_kingpin_m is not None:
        front = check_number(p.front_from_kingpin_m, f"{path}.front_from_kingpin_m", minimum=-math.inf)
        how = "as given"
    elif deck is not None:
        front = deck.front_from_kingpin_m + (deck.length_m - length) / 2.0
        how = "centred on the deck"
    else:
        raise InvalidVehicle(
            f"{path}.front_from_kingpin_m is needed (no deck to centre the load on)",
            field=f"{path}.front_from_kingpin_m",
        )
    if deck is not None and (
        front < deck.front_from_kingpin_m - 1e-9 or front + length > deck.front_from_kingpin_m + deck.length_m + 1e-9
    ):
        raise InvalidVehicle(
            f"{path} spans {front:g}-{front + length:g} m behind the kingpin, outside the deck "
            f"({deck.front_from_kingpin_m:g}-{deck.front_from_kingpin_m + deck.length_m:g} m)",
            field=f"{path}.front_from_kingpin_m" if p.front_from_kingpin_m is not None else f"{path}.length_m",
            value=front,
        )
    return front, length, how


def _deck_load_heights(p: PayloadSpec, path: str) -> tuple[float, float, float, float]:
    deck0 = check_number(p.deck_height_m, f"{path}.deck_height_m")
    top0 = check_number(
        p.load_height_m,
        f"{path}.load_height_m",
        minimum=deck0,
        reason=f" (the top of the load must be above the deck, {deck0:g} m)",
    )
    deck1 = deck0 if p.deck_height_rear_m is None else check_number(p.deck_height_rear_m, f"{path}.deck_height_rear_m")
    if p.load_height_rear_m is None:
        top1 = deck1 + (top0 - deck0)  # load top parallel to the deck
    else:
        top1 = check_number(
            p.load_height_rear_m,
            f"{path}.load_height_rear_m",
            minimum=deck1,
            strict=False,
            reason=f" (the top of the load may not be below the deck, {deck1:g} m)",
        )
    return deck0, deck1, top0, top1


def payload_item(p: PayloadSpec, deck: DeckSpec | None, path: str) -> MassItem:
    if not isinstance(p, PayloadSpec):
        raise InvalidVehicle(f"{path} must be a payload", field=path, value=p)
    mass = check_number(p.mass_kg, f"{path}.mass_kg", strict=False)
    modes = [
        n
        for n, v in (("deck_height_m", p.deck_height_m), ("cg_height_m", p.cg_height_m), ("tank", p.tank))
        if v is not None
    ]
    if len(modes) != 1:
        raise InvalidVehicle(
            f"{path} needs exactly one of deck_height_m (with load_height_m), cg_height_m or tank; got "
            f"{', '.join(modes) or 'none'}",
            field=f"{path}.{modes[1] if len(modes) > 1 else 'deck_height_m'}",
        )
    if p.cg_from_kingpin_m is not None:
        if p.front_from_kingpin_m is not None or p.length_m is not None:
            raise InvalidVehicle(
                f"give {path}.cg_from_kingpin_m or the load's extent (front_from_kingpin_m, length_m), not both",
                field=f"{path}.cg_from_kingpin_m",
            )
        x_cg, x_how = check_number(p.cg_from_kingpin_m, f"{path}.cg_from_kingpin_m", minimum=-math.inf), "as given"
        front = length = None
    else:
        front, length, x_how = _payload_extent(p, deck, path)
        x_cg = front + length / 2.0
    stray = [n for n in ("load_height_m", "deck_height_rear_m", "load_height_rear_m") if getattr(p, n) is not None]
    if modes[0] != "deck_height_m" and stray:
        raise InvalidVehicle(
            f"{path}.{stray[0]} applies to a deck load only (with deck_height_m), not with {modes[0]}",
            field=f"{path}.{stray[0]}",
        )
    if modes[0] == "cg_height_m":
        z, z_how = check_number(p.cg_height_m, f"{path}.cg_height_m"), "CG height as given"
    elif modes[0] == "tank":
        z, z_how = _tank_cg(p.tank, f"{path}.tank")
    else:
        z, z_how, x_cg = _deck_cg(p, path, front, length, x_cg)
    return MassItem(path.removeprefix("spec."), mass, z, x_cg, f"{z_how}; longitudinal: {x_how}")


def _deck_cg(p: PayloadSpec, path: str, front: float | None, length: float | None, x_cg: float):
    f = LOAD_DISTRIBUTIONS[check_choice(p.distribution, f"{path}.distribution", tuple(LOAD_DISTRIBUTIONS))]
    deck0, deck1, top0, top1 = _deck_load_heights(p, path)
    if deck0 == deck1 and top0 == top1:
        return deck0 + f * (top0 - deck0), f"{p.distribution}: z = deck + {f:g} (load - deck)", x_cg
    if length is None:
        raise InvalidVehicle(
            f"a sloping deck needs the load's length: give {path}.length_m (or the deck) instead of cg_from_kingpin_m",
            field=f"{path}.length_m",
        )
    s_bar, z = sloped_load_centroid(length, deck0, deck1, top0, top1, f)
    return z, f"{p.distribution} on a sloping deck: centroid of the side-view trapezoid", front + s_bar


def _tank_cg(t: TankSpec, path: str) -> tuple[float, str]:
    if not isinstance(t, TankSpec):
        raise InvalidVehicle(f"{path} must be a tank", field=path, value=t)
    shape = check_choice(t.shape, f"{path}.shape", TANK_SHAPES)
    height = check_number(t.height_m, f"{path}.height_m")
    bottom = check_number(t.bottom_height_m, f"{path}.bottom_height_m")
    if (t.fill_height_m is None) == (t.fill_fraction is None):
        raise InvalidVehicle(
            f"give exactly one of {path}.fill_height_m or fill_fraction", field=f"{path}.fill_height_m"
        )
    if t.fill_height_m is not None:
        depth = check_number(t.fill_height_m, f"{path}.fill_height_m")
        if depth > height:
            raise InvalidVehicle(
                f"{path}.fill_height_m = {depth:g} m exceeds the tank's height {height:g} m",
                field=f"{path}.fill_height_m",
                value=depth,
            )
        z = tank_liquid_cg_height_m(height, bottom, fill_height_m=depth)
        fill = f"depth {depth:g} m"
    else:
        frac = check_number(t.fill_fraction, f"{path}.fill_fraction")
        if frac > 1:
            raise InvalidVehicle(
                f"{path}.fill_fraction must be in (0, 1], got {frac:g}", field=f"{path}.fill_fraction", value=frac
            )
        z = tank_liquid_cg_height_m(height, bottom, fill_fraction=frac)
        fill = f"{100 * frac:g} % full by volume"
    return z, f"liquid in a {shape} tank ({fill}): centroid of the liquid segment (circular-segment closed form)"


def tare_item(t: TareSpec, deck_heights: Sequence[float], wheelbase: float) -> tuple[MassItem, str | None]:
    if not isinstance(t, TareSpec):
        raise InvalidVehicle("spec.tare must be a tare mass", field="spec.tare", value=t)
    mass = check_number(t.mass_kg, "spec.tare.mass_kg")
    note = None
    if t.cg_height_m is not None:
        z, z_how = check_number(t.cg_height_m, "spec.tare.cg_height_m"), "CG height as given"
    else:
        if not deck_heights:
            raise InvalidVehicle(
                "spec.tare.cg_height_m is needed (no deck height to default it to)", field="spec.tare.cg_height_m"
            )
        z = min(deck_heights)
        z_how = "default (assumed): at the lowest deck height"
        note = (
            f"tare CG height assumed at the lowest deck height ({z:g} m): no published body-type default was found; "
            "conservative for a flat-deck or skeletal trailer whose chassis and axles lie below the deck, not for a "
            "body or tank built above it; give spec.tare.cg_height_m"
        )
    if (t.cg_from_kingpin_m is None) == (t.rear_group_load_kg is None):
        raise InvalidVehicle(
            "give exactly one of spec.tare.cg_from_kingpin_m or spec.tare.rear_group_load_kg",
            field="spec.tare.cg_from_kingpin_m",
        )
    if t.cg_from_kingpin_m is not None:
        x, x_how = check_number(t.cg_from_kingpin_m, "spec.tare.cg_from_kingpin_m", minimum=-math.inf), "as given"
    else:
        rear = check_number(t.rear_group_load_kg, "spec.tare.rear_group_load_kg")
        x = wheelbase * rear / mass  # lever rule about the kingpin (Eq. 4.27 at rest)
        x_how = f"lever rule x = L m_rear / m = {wheelbase:g} x {rear:g} / {mass:g} (Eq. 4.27 at rest)"
    return MassItem("tare", mass, z, x, f"{z_how}; longitudinal: {x_how}"), note
