"""The combination builder: every unit of a combination from measurable data -> the roll model's
:class:`~engine.vehicle.combination.Combination`, every component value with its source.

A :class:`CombinationSpec` lists the units front to rear (rigid truck, tractor, semitrailer, B-train lead trailer,
converter dolly, full trailer) and the couplings between them. Each unit is given as the single-unit builder takes
it (:class:`~engine.builder.VehicleSpec`): its axle groups (axles, tyres per axle, track, position, tyre
size, suspension type), its tare mass with its CG, and its payloads (mass with a CG height, or deck and load
heights, or a tank), on its deck. Positions are metres behind the unit's reference point
(:data:`engine.vehicle.combination.UNIT_KINDS`): a tractor's or rigid truck's front group centre, a semitrailer's or
lead trailer's kingpin, a dolly's or full trailer's drawbar eye; the single-unit specs' ``*_from_kingpin_m``
fields (tare, payloads, deck) are measured from that reference point.

:func:`build_combination` fills, per axle group:

* the tyre's vertical rate from its size (:func:`engine.vehicle.roll_tyre_for_size`), and its static loaded radius;
* the suspension's roll stiffness per axle, roll-centre height, spring spacing and lash, the axle's unsprung mass and
  its CG height (:func:`engine.vehicle.get_roll_suspension`; the unsprung CG defaults to the loaded radius of the
  tyre when no suspension type is named);
* explicit values win over the library's (``method`` ``given``), and each value keeps its source;

per coupling: a fifth wheel's roll stiffness and lash from the library (:func:`engine.vehicle.get_fifth_wheel`) or
as given; a pintle (drawbar) or an A-dolly's ball coupling passes no roll moment (the record's ``pintle``);

per unit: the tare and payload masses and CGs exactly as the single-unit builder computes them
(:func:`~engine.builder.payloads.tare_item`, :func:`~engine.builder.payloads.payload_item`), composited as the
single-unit builder composites them, and the **sprung** mass and CG the roll model takes: the tare includes the
axles (as a weighbridge weighs it), so the axles' unsprung masses are taken out at their CGs,
``m_s = sum(m) - n m_u``, ``z_s = (sum(m z) - n m_u z_u) / m_s`` (as the presets derive it from a thesis record,
:func:`engine.vehicle.combination_presets.unit_from_record`).

The combination is then checked by :func:`engine.vehicle.validate_combination` (the chain, plausible ranges with
the likely unit slip, roll centres below the CG, fifth wheels on their groups, every support loaded), its errors
re-pointed at the spec field behind the record field; the static axle loads are
:func:`engine.vehicle.combination.static_loads`. Masses and heights the user types are first checked against
:data:`engine.vehicle.plausibility.RANGES`: a 31.5 kg semitrailer tare is refused with "typed in tonnes?".

References
----------
.. [1] Moreno (thesis), Eq. 2.11, Eq. 4.27; the single-unit builder (:mod:`engine.builder`).
.. [2] TruckSim 2022.1 example database (the roll component library, :mod:`engine.vehicle.roll_components`).
"""

from __future__ import annotations

import dataclasses
import math
import re
import typing
from dataclasses import asdict, dataclass

from engine.builder.build import _composite
from engine.builder.combination_spec import (
    ROOT,
    CombinationSpec,
    CouplingSpec,
    RollSuspensionSpec,
    RollTyreSpec,
    UnitGroupSpec,
    UnitSpec,
)
from engine.builder.last_unit import last_unit_record
from engine.builder.payloads import payload_item, tare_item
from engine.builder.plausible import check_payloads_plausible
from engine.builder.spec import (
    DeckSpec,
    FieldDerivation,
    MassItem,
    PayloadSpec,
    TareSpec,
    check_choice,
    check_count,
    check_number,
)
from engine.errors import InvalidInput, InvalidVehicle
from engine.vehicle.combination import (
    G_M_PER_S2,
    LEADING_KINDS,
    UNIT_KINDS,
    AxleGroup,
    Combination,
    Coupling,
    Unit,
    static_loads,
    validate_combination,
)
from engine.vehicle.dynamic_data import DynamicsData, GroupData, UnitData
from engine.vehicle.plausibility import check_plausible
from engine.vehicle.roll_components import (
    FIFTH_WHEELS,
    SUSPENSIONS_IN_ROLL,
    get_fifth_wheel,
    get_roll_suspension,
    roll_tyre_for_size,
)

#: the coupling kinds a spec may name: the record's kinds, and ``ball`` (an A-dolly's ball coupling: a pintle)
SPEC_COUPLING_KINDS = ("fifth-wheel", "b-coupling", "pintle", "ball")
#: default group ids per unit kind (front to rear)
_GROUP_IDS = {"tractor": ("steer", "drive"), "rigid-truck": ("steer", "drive"), "full-trailer": ("front", "rear")}

# --------------------------------------------------------------------------------------------- the build


@dataclass(frozen=True)
class BuiltUnit:
    """One unit's masses: the items (tare, payloads), their total and CG, and the sprung mass and CG the roll model
    takes (the axles taken out).

    positions are behind the unit's reference point [m]; heights above the road [m]; masses [kg]
    """

    id: str
    kind: str
    masses: tuple[MassItem, ...]
    mass_kg: float
    cg_height_m: float
    cg_position_m: float
    unsprung_mass_kg: float
    sprung_mass_kg: float
    sprung_cg_height_m: float
    sprung_cg_position_m: float


@dataclass(frozen=True)
class GroupLoad:
    """The static normal load on one axle group (level road), from :func:`engine.vehicle.combination.static_loads`."""

    unit: str
    group: str
    load_kn: float
    load_kg: float
    per_axle_kg: float


@dataclass(frozen=True)
class BuiltCombination:
    """The combination record, every component value with its derivation, each unit's masses and the static loads."""

    combination: Combination
    derivation: dict[str, FieldDerivation]  # record path (units[0].groups[1].tyre_stiffness_kn_per_m) -> how
    units: tuple[BuiltUnit, ...]
    axle_loads: tuple[GroupLoad, ...]
    coupling_loads_kn: tuple[float, ...]
    gross_mass_kg: float
    notes: tuple[str, ...] = ()
    #: the spec's data for the yaw-roll model, by the built unit and group ids, ``given_at`` the spec paths; the
    #: combination (the static record) does not hold it, so the static answers do not depend on it
    dynamics: DynamicsData = dataclasses.field(default_factory=DynamicsData)

    def to_dict(self) -> dict[str, typing.Any]:
        return {
            "combination": self.combination.to_dict()["combination"],
            "derivation": {k: asdict(v) for k, v in self.derivation.items()},
            "units": [asdict(u) for u in self.units],
            "axle_loads": [asdict(a) for a in self.axle_loads],
            "coupling_loads_kn": list(self.coupling_loads_kn),
            "gross_mass_kg": self.gross_mass_kg,
            "notes": list(self.notes),
            "dynamics": self.dynamics.as_lists(),
        }


# --------------------------------------------------------------------------------------------- the build


class _Book:
    """The derivations of one build, and the record path -> spec path map for re-pointing the record's errors."""

    def __init__(self) -> None:
        self.derivation: dict[str, FieldDerivation] = {}
        self.spec_path: dict[str, str] = {}

    def put(self, rec: str, value, unit: str, method: str, explanation: str, source: str, spec: str):
        self.derivation[rec] = FieldDerivation(rec, value, unit, method, explanation, source, spec)
        self.spec_path[rec] = spec
        return value

    def pick(self, rec: str, given, library, unit: str, spec: str, lib_spec: str, name: str, quantity: str | None):
        """The given value (checked as plausible ``quantity``) or the library's (a Sourced); None if neither."""
        if given is not None:
            v = check_plausible(quantity, given, spec, name) if quantity else check_number(given, spec)
            return self.put(rec, v, unit, "given", f"{name} as given", spec, spec)
        if library is not None:
            return self.put(rec, library.value, unit, "library", f"{name} from the component library",
                            library.source, lib_spec)  # fmt: skip
        return None


def _need(value, spec: str, what: str):
    if value is None:
        raise InvalidVehicle(f"{spec} is needed: {what}", field=spec)
    return value


def _group(book: _Book, g: UnitGroupSpec, gid: str, steer: bool, rec: str, path: str, what: str) -> AxleGroup:
    if not isinstance(g, UnitGroupSpec):
        raise InvalidVehicle(f"{path} must be an axle group", field=path, value=g)
    tyres = check_count(g.tyres_per_axle, f"{path}.tyres_per_axle", (2, 4))
    axles = check_count(g.axles, f"{path}.axles")
    book.spec_path[f"{rec}.axles"], book.spec_path[f"{rec}.tyres_per_axle"] = f"{path}.axles", f"{path}.tyres_per_axle"
    track = book.put(f"{rec}.track_m", check_plausible("track_m", g.track_m, f"{path}.track_m", what), "m", "given",
                     "T as given", f"{path}.track_m", f"{path}.track_m")  # fmt: skip
    pos = check_plausible("position_m", g.position_m, f"{path}.position_m", what)
    book.put(f"{rec}.position_m", pos, "m", "given", "position as given", f"{path}.position_m", f"{path}.position_m")
    if g.axle_spacing_m is not None:
        check_plausible("axle_spacing_m", g.axle_spacing_m, f"{path}.axle_spacing_m", f"the axle spacing of {what}")
    # tyre
    ts, tp = g.tyre, f"{path}.tyre"
    if not isinstance(ts, RollTyreSpec):
        raise InvalidVehicle(f"{tp} must be a tyre", field=tp, value=ts)
    tyre = roll_tyre_for_size(ts.size, field=f"{tp}.size") if ts.size is not None else None
    lib_lr = None
    if tyre is not None:
        lib_lr = dataclasses.replace(tyre.free_radius_m, value=tyre.loaded_radius_m)
        lib_lr = dataclasses.replace(
            lib_lr, source=f"computed: R0 - Fz/Cz at the rated {tyre.rated_load_kg.value:g} kg "
            f"(R0: {tyre.free_radius_m.source}; Cz: {tyre.stiffness_kn_per_m.source})"
        )  # fmt: skip
    kt = book.pick(f"{rec}.tyre_stiffness_kn_per_m", ts.stiffness_kn_per_m, tyre and tyre.stiffness_kn_per_m, "kN/m",
                   f"{tp}.stiffness_kn_per_m", f"{tp}.size", "kT", "tyre_stiffness_kn_per_m")  # fmt: skip
    _need(kt, f"{tp}.size", f"the tyre's vertical rate of {what} (or give {tp}.stiffness_kn_per_m)")
    lr = book.pick(f"{rec}.tyre_loaded_radius_m", ts.loaded_radius_m, lib_lr, "m", f"{tp}.loaded_radius_m",
                   f"{tp}.size", "lr", "tyre_radius_m")  # fmt: skip
    # suspension
    ss, sp = g.suspension, f"{path}.suspension"
    if not isinstance(ss, RollSuspensionSpec):
        raise InvalidVehicle(f"{sp} must be a suspension", field=sp, value=ss)
    s = get_roll_suspension(ss.type, field=f"{sp}.type") if ss.type is not None else None
    alt = f"(or give {sp}.type)"
    values = {}
    for name, unit, quantity, sym in (
        ("roll_stiffness_knm_per_rad", "kN m/rad", "suspension_roll_stiffness_knm_per_rad", "k_theta"),
        ("roll_centre_height_m", "m", "height_m", "roll-centre height"),
        ("spring_spacing_m", "m", "spring_spacing_m", "b"),
        ("lash_deg", "deg", "lash_deg", "lash"),
        ("unsprung_mass_kg", "kg", "unsprung_mass_kg", "unsprung mass"),
        ("unsprung_cg_height_m", "m", "height_m", "unsprung CG height"),
    ):
        values[name] = book.pick(f"{rec}.{name}", getattr(ss, name), s and getattr(s, name), unit, f"{sp}.{name}",
                                 f"{sp}.type", sym, quantity)  # fmt: skip
    if values["unsprung_cg_height_m"] is None and lr is not None:
        d = book.derivation[f"{rec}.tyre_loaded_radius_m"]
        values["unsprung_cg_height_m"] = book.put(
            f"{rec}.unsprung_cg_height_m", lr, "m", "computed", "the axle centre: the tyre's loaded radius lr",
            d.source, d.spec_path or f"{tp}.size",
        )  # fmt: skip
    if values["lash_deg"] is None:
        values["lash_deg"] = book.put(f"{rec}.lash_deg", 0.0, "deg", "default", "no lash",
                                      "assumed: none given (no readable source gives a suspension lash)",
                                      f"{sp}.lash_deg")  # fmt: skip
    for name, what_else in (
        ("roll_stiffness_knm_per_rad", "the suspension's roll stiffness"),
        ("roll_centre_height_m", "the roll-centre height"),
        ("unsprung_mass_kg", "the axle's unsprung mass"),
        ("unsprung_cg_height_m", "the axle's CG height (or a tyre size or loaded radius)"),
    ):
        _need(values[name], f"{sp}.{name}", f"{what_else} of {what} {alt}")
    return AxleGroup(
        gid, axles, tyres, track, pos, kt, values["roll_stiffness_knm_per_rad"], values["roll_centre_height_m"],
        values["unsprung_mass_kg"], values["unsprung_cg_height_m"], lash_deg=values["lash_deg"],
        spring_spacing_m=values["spring_spacing_m"], steer=steer,
    )  # fmt: skip


_TARE_PATH = re.compile(r"^spec\.tare")


def _tare(t: TareSpec, deck_heights: list[float], groups: tuple[AxleGroup, ...], path: str, what: str):
    """The single-unit builder's tare item, its errors under ``path``; the rear-group-load lever rule measured from
    the front support (the reference point, or a full trailer's front group)."""
    if isinstance(t, TareSpec):
        check_plausible("unit_mass_kg", t.mass_kg, f"{path}.mass_kg", f"the tare of {what}")
        if t.cg_height_m is not None:
            check_plausible("height_m", t.cg_height_m, f"{path}.cg_height_m", f"the tare CG of {what}")
        if t.cg_from_kingpin_m is not None:
            check_plausible("position_m", t.cg_from_kingpin_m, f"{path}.cg_from_kingpin_m", f"the tare CG of {what}")
        if t.rear_group_load_kg is not None:
            load = t.rear_group_load_kg
            check_plausible("group_load_kg", load, f"{path}.rear_group_load_kg", f"the tare rear load of {what}")
    x0 = groups[0].position_m if len(groups) == 2 and groups[0].position_m != 0 else 0.0
    span = groups[-1].position_m - x0
    try:
        item, note = tare_item(t, deck_heights, span)
    except InvalidInput as e:
        raise type(e)(_TARE_PATH.sub(path, str(e)), field=_TARE_PATH.sub(path, e.field or ""), value=e.value) from e
    if t.rear_group_load_kg is not None:
        item = dataclasses.replace(item, cg_from_kingpin_m=x0 + item.cg_from_kingpin_m)
    return item, note and note.replace("spec.tare", path)


def _payloads(u: UnitSpec, path: str, what: str) -> tuple[list[MassItem], list[float]]:
    deck = u.deck
    if deck is not None:
        if not isinstance(deck, DeckSpec):
            raise InvalidVehicle(f"{path}.deck must be a deck", field=f"{path}.deck", value=deck)
        deck = DeckSpec(
            check_plausible("position_m", deck.front_from_kingpin_m, f"{path}.deck.front_from_kingpin_m", what),
            check_plausible("length_m", deck.length_m, f"{path}.deck.length_m", what),
        )
    # the single-unit spec's rule: a payload of 22 (or 5, or 0.5) kg is tonnes typed as kg; it lifted a tractor-
    # semitrailer's SRT from 0.503 to 0.846 g here while the same spec payload was refused
    check_payloads_plausible(u.payloads, path)
    items, decks = [], []
    for k, p in enumerate(u.payloads or ()):
        pp = f"{path}.payloads[{k}]"
        if isinstance(p, PayloadSpec) and p.deck_height_m is not None:
            decks.append(p.deck_height_m)
        item = payload_item(p, deck, pp)
        items.append(dataclasses.replace(item, name=f"payloads[{k}]"))
    return items, decks


def _unit(book: _Book, u: UnitSpec, i: int, uid: str, path: str) -> tuple[Unit, BuiltUnit, list[str]]:
    if not isinstance(u, UnitSpec):
        raise InvalidVehicle(f"{path} must be a unit", field=path, value=u)
    kind = check_choice(u.kind, f"{path}.kind", tuple(UNIT_KINDS))
    book.spec_path[f"units[{i}].kind"] = f"{path}.kind"
    book.spec_path[f"units[{i}].id"] = f"{path}.id"
    what = f"the {kind} {uid!r}"
    ref, n = UNIT_KINDS[kind]
    specs = tuple(u.axle_groups or ())
    if len(specs) != n:
        raise InvalidVehicle(
            f"{what} has {n} axle group(s) (one load-sharing group under each support), got {len(specs)}",
            field=f"{path}.axle_groups",
        )
    ids = _GROUP_IDS.get(kind, (uid,))
    groups = tuple(
        _group(book, g, g.id if isinstance(g, UnitGroupSpec) and g.id is not None else ids[j],
               kind in LEADING_KINDS and j == 0, f"units[{i}].groups[{j}]", f"{path}.axle_groups[{j}]",
               f"group {j} of {what}")
        for j, g in enumerate(specs)
    )  # fmt: skip
    loads, decks = _payloads(u, path, what)
    tare, note = _tare(u.tare, decks, groups, f"{path}.tare", what)
    items = (tare, *loads)
    mass, z, x = _composite(items)
    m_u = sum(g.axles * g.unsprung_mass_kg for g in groups)
    sprung = mass - m_u
    if not sprung > 0:
        raise InvalidVehicle(
            f"{path}.tare.mass_kg: the tare and payloads of {what} ({mass:g} kg) do not exceed its axles' unsprung "
            f"mass ({m_u:g} kg): the tare is weighed with its axles",
            field=f"{path}.tare.mass_kg",
            value=mass,
        )
    z_s = (mass * z - sum(g.axles * g.unsprung_mass_kg * g.unsprung_cg_height_m for g in groups)) / sprung
    x_s = (mass * x - sum(g.axles * g.unsprung_mass_kg * g.position_m for g in groups)) / sprung
    terms = " + ".join(f"{it.mass_kg:g}" for it in items)
    sources = f"{path}.tare and {path}.payloads; the axles' unsprung masses"
    book.put(f"units[{i}].sprung_mass_kg", sprung, "kg", "computed",
             f"m_s = ({terms}) - {m_u:g} (axles)", sources, f"{path}.tare.mass_kg")  # fmt: skip
    book.put(f"units[{i}].cg_height_m", z_s, "m", "computed",
             f"z_s = (sum(m z) - sum(m_u z_u)) / m_s, sum(m z)/sum(m) = {z:.4f}", sources,
             f"{path}.tare.cg_height_m")  # fmt: skip
    book.put(f"units[{i}].cg_position_m", x_s, "m", "computed",
             f"x_s = (sum(m x) - sum(m_u x_u)) / m_s behind {ref}, sum(m x)/sum(m) = {x:.4f}", sources,
             f"{path}.tare.cg_from_kingpin_m")  # fmt: skip
    unit = Unit(uid, kind, sprung, z_s, x_s, groups, title=u.title)
    built = BuiltUnit(uid, kind, items, mass, z, x, m_u, sprung, z_s, x_s)
    notes = [f"{path}: {note}"] if note else []
    if any(isinstance(g, UnitGroupSpec) and g.axle_spacing_m is not None for g in specs):
        notes.append(
            f"{path}: axle spacing is used by the yaw-roll model only: the roll model has one equivalent axle per group"
        )
    return unit, built, notes


def _coupling(book: _Book, cs: CouplingSpec, k: int, towing: Unit) -> Coupling:
    path, rec = f"{ROOT}.couplings[{k}]", f"couplings[{k}]"
    if not isinstance(cs, CouplingSpec):
        raise InvalidVehicle(f"{path} must be a coupling", field=path, value=cs)
    kind = check_choice(cs.kind, f"{path}.kind", SPEC_COUPLING_KINDS)
    book.spec_path[f"{rec}.kind"] = f"{path}.kind"
    what = f"the {kind} behind the {towing.kind} {towing.id!r}"
    pos = check_plausible("position_m", cs.position_m, f"{path}.position_m", what)
    h = check_plausible("height_m", cs.height_m, f"{path}.height_m", what)
    book.put(f"{rec}.position_m", pos, "m", "given", "position as given", f"{path}.position_m", f"{path}.position_m")
    book.put(f"{rec}.height_m", h, "m", "given", "height as given", f"{path}.height_m", f"{path}.height_m")
    if kind in ("pintle", "ball"):
        for name in ("fifth_wheel", "roll_stiffness_knm_per_rad", "lash_deg"):
            if getattr(cs, name) not in (None, 0, 0.0):
                raise InvalidVehicle(
                    f"{path}.{name}: a {kind} passes no roll moment; leave it out", field=f"{path}.{name}",
                    value=getattr(cs, name),
                )  # fmt: skip
        book.put(f"{rec}.roll_stiffness_knm_per_rad", None, "kN m/rad", "default", "no roll moment",
                 f"a {kind} is free in roll", f"{path}.kind")  # fmt: skip
        return Coupling("pintle", pos, h)
    fw = get_fifth_wheel(cs.fifth_wheel, field=f"{path}.fifth_wheel") if cs.fifth_wheel is not None else None
    k_roll = book.pick(f"{rec}.roll_stiffness_knm_per_rad", cs.roll_stiffness_knm_per_rad,
                       fw and fw.roll_stiffness_knm_per_rad, "kN m/rad", f"{path}.roll_stiffness_knm_per_rad",
                       f"{path}.fifth_wheel", "roll stiffness", "coupling_roll_stiffness_knm_per_rad")  # fmt: skip
    _need(k_roll, f"{path}.fifth_wheel", f"the roll stiffness of {what} (or give {path}.roll_stiffness_knm_per_rad)")
    lash = book.pick(f"{rec}.lash_deg", cs.lash_deg, fw and fw.lash_deg, "deg", f"{path}.lash_deg",
                     f"{path}.fifth_wheel", "lash", "lash_deg")  # fmt: skip
    if lash is None:
        lash = book.put(f"{rec}.lash_deg", 0.0, "deg", "default", "no lash", "assumed: none given", f"{path}.lash_deg")
    return Coupling(kind, pos, h, k_roll, lash)


_INDEX = re.compile(r"^combination\.(.*)$")


def _repoint(e: InvalidInput, book: _Book) -> InvalidInput:
    """An error of :func:`validate_combination` (``combination.units[1].groups[0].track_m``) at the spec field
    behind it (``combination_spec.units[1].axle_groups[0].track_m``)."""
    m = _INDEX.match(e.field or "")
    rec = m.group(1) if m else ""
    spec = book.spec_path.get(rec)
    if spec is None:  # a field with no one input behind it: its unit, group or coupling
        parent = rec
        while spec is None and "." in parent:
            parent = parent.rsplit(".", 1)[0]
            spec = book.spec_path.get(f"{parent}.kind") or book.spec_path.get(f"{parent}.axles")
            if spec is not None:
                spec = spec.rsplit(".", 1)[0]
        spec = spec or ROOT
    return type(e)(f"{e} (record field {rec or e.field}, from {spec})", field=spec, value=e.value)


def build_combination(spec: CombinationSpec) -> BuiltCombination:
    """The whole-combination roll model's record for a measurable spec, every component value with its source.

    Parameters
    ----------
    spec : the combination in measurable terms (:class:`CombinationSpec`)

    Returns
    -------
    BuiltCombination with ``combination`` (validated by :func:`engine.vehicle.validate_combination`), ``derivation``
    (record path -> value, method, explanation, source, spec path), each unit's masses, sprung mass and CG, and the
    static axle loads (:func:`engine.vehicle.combination.static_loads`, level road) [kN and kg].

    Raises
    ------
    InvalidVehicle : naming the spec field as typed (``combination_spec.units[2].axle_groups[0].tyre.size``), with
        the likely unit slip for a value outside a heavy vehicle's range.
    """
    if not isinstance(spec, CombinationSpec):
        raise InvalidVehicle("the combination spec must be a CombinationSpec", field=ROOT, value=spec)
    units_in = tuple(spec.units or ())
    if not units_in:
        raise InvalidVehicle("a combination has at least one unit", field=f"{ROOT}.units")
    if len(units_in) > 8:
        raise InvalidVehicle("a combination has at most 8 units", field=f"{ROOT}.units")
    couplings_in = tuple(spec.couplings or ())
    if len(couplings_in) != len(units_in) - 1:
        raise InvalidVehicle(
            f"{len(units_in)} units need {len(units_in) - 1} couplings (one between each two), got {len(couplings_in)}",
            field=f"{ROOT}.couplings",
        )
    kinds = [getattr(u, "kind", None) for u in units_in]
    book, units, built, notes = _Book(), [], [], []
    for i, u in enumerate(units_in):
        uid = getattr(u, "id", None)
        if uid is None:
            kind = kinds[i] if isinstance(kinds[i], str) else "unit"
            uid = kind if kinds.count(kind) == 1 else f"{kind}{kinds[: i + 1].count(kind)}"
        unit, b, n = _unit(book, u, i, uid, f"{ROOT}.units[{i}]")
        units.append(unit)
        built.append(b)
        notes += n
    couplings = [_coupling(book, cs, k, units[k]) for k, cs in enumerate(couplings_in)]
    dynamics = _dynamics(units_in, units)
    c = Combination(tuple(units), tuple(couplings), spec.title, None, spec.front_llt_ratio)
    try:
        validate_combination(c)
    except InvalidInput as e:
        if e.field == "combination.front_llt_ratio":
            raise type(e)(str(e), field=f"{ROOT}.front_llt_ratio", value=e.value) from e
        raise _repoint(e, book) from e
    st = static_loads(c)
    axle_loads = []
    for i, u in enumerate(c.units):
        for j, g in enumerate(u.groups):
            kn = st.normal_kn[(i, j)]
            kg = kn * 1000.0 / G_M_PER_S2
            axle_loads.append(GroupLoad(u.id, g.id, kn, kg, kg / g.axles))
            rated = None
            size = units_in[i].axle_groups[j].tyre.size
            if size is not None:
                rated = roll_tyre_for_size(size).rated_load_kg.value
            per_tyre = kg / (g.axles * g.tyres_per_axle)
            if rated is not None and per_tyre > rated:
                notes.append(
                    f"{ROOT}.units[{i}].axle_groups[{j}]: each tyre carries {per_tyre:.0f} kg at rest, above the "
                    f"library tyre's rated {rated:g} kg"
                )
    coupling_loads = tuple(st.coupling_kn[k] for k in range(len(c.couplings)))
    # the last unit's thesis record for its 3D model (LLTf/LLTr from the combination)
    record, note = last_unit_record(spec, c, book.derivation)
    c = dataclasses.replace(c, last_unit_record=record)
    notes.append(note)
    gross = sum(b.mass_kg for b in built)
    if not math.isfinite(gross):  # pragma: no cover - every mass is checked finite above
        raise InvalidVehicle("the masses are not finite", field=f"{ROOT}.units")
    return BuiltCombination(c, book.derivation, tuple(built), tuple(axle_loads), coupling_loads, gross, tuple(notes),
                            dynamics)  # fmt: skip


def _given_fields(data: UnitData | GroupData, path: str) -> dict[str, typing.Any]:
    """The given fields of one unit's or group's dynamic data, numbers checked finite; the yaw-roll model checks
    their ranges where it takes them (:func:`engine.dynamics.parameters.resolve`)."""
    out = {}
    for f in dataclasses.fields(data):
        v = getattr(data, f.name)
        if v is not None:
            out[f.name] = v if f.name == "tyre_type" else check_number(v, f"{path}.{f.name}")
    return out


def _dynamics(units_in: tuple[UnitSpec, ...], units: list[Unit]) -> DynamicsData:
    """The spec's data for the yaw-roll model by the built ids, each value with the spec path it was typed at; a
    group's ``axle_spacing_m`` is its spacing (given once, on the group)."""
    out_units: dict[str, UnitData] = {}
    out_groups: dict[tuple[str, str], GroupData] = {}
    given_at: dict[str, str] = {}
    for i, (us, u) in enumerate(zip(units_in, units, strict=True)):
        path = f"{ROOT}.units[{i}]"
        if us.dynamics is not None:
            if not isinstance(us.dynamics, UnitData):
                raise InvalidVehicle(f"{path}.dynamics must be an object", field=f"{path}.dynamics", value=us.dynamics)
            fields = _given_fields(us.dynamics, f"{path}.dynamics")
            if fields:
                out_units[u.id] = UnitData(**fields)
                given_at.update({f"units[{u.id}].{k}": f"{path}.dynamics.{k}" for k in fields})
        for j, (gs, g) in enumerate(zip(us.axle_groups, u.groups, strict=True)):
            gpath = f"{path}.axle_groups[{j}]"
            fields = {}
            if gs.dynamics is not None:
                if not isinstance(gs.dynamics, GroupData):
                    raise InvalidVehicle(f"{gpath}.dynamics must be an object", field=f"{gpath}.dynamics",
                                         value=gs.dynamics)  # fmt: skip
                spacing = gs.dynamics.axle_spacing_m
                if spacing is not None:
                    raise InvalidVehicle(f"{gpath}.dynamics.axle_spacing_m: the group's spacing is "
                                         f"{gpath}.axle_spacing_m", field=f"{gpath}.dynamics.axle_spacing_m",
                                         value=spacing)  # fmt: skip
                fields = _given_fields(gs.dynamics, f"{gpath}.dynamics")
                given_at.update({f"groups[{u.id}/{g.id}].{k}": f"{gpath}.dynamics.{k}" for k in fields})
            if gs.axle_spacing_m is not None:
                fields["axle_spacing_m"] = gs.axle_spacing_m
                given_at[f"groups[{u.id}/{g.id}].axle_spacing_m"] = f"{gpath}.axle_spacing_m"
            if fields:
                out_groups[(u.id, g.id)] = GroupData(**fields)
    return DynamicsData(out_units, out_groups, given_at)


#: the library a spec can name: roll suspensions, tyre sizes (through :func:`roll_tyre_for_size`), fifth wheels
SPEC_LIBRARY = {"suspensions": tuple(SUSPENSIONS_IN_ROLL), "fifth_wheels": tuple(FIFTH_WHEELS)}
