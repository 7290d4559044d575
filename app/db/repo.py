"""Persistence of saved vehicles and fleets: each function is one transaction on a :class:`Database`.

Plain values in and out (the stored JSON text is returned as text: ``app.catalog.service`` parses and validates it),
and the errors below; no HTTP here. Every query is scoped to the owner: another owner's row is "not found".

Writes take the owner's write lock (:meth:`Database.write`) and check what they must under it: the count
limits, the expected version (``If-Match``), the fleet members, the fleets that use a vehicle. The version check
is also in the ``UPDATE``'s ``WHERE`` and the membership is also a foreign key, so a bug in the locking could not
lose an update or leave a fleet pointing at a deleted vehicle.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from datetime import UTC, datetime

from sqlalchemy import Select, and_, delete, func, or_, select, update
from sqlalchemy.orm import Session

from .models import FleetMemberRow, FleetRow, VehicleRow
from .session import Database

#: ``expected`` versions of a conditional write: a set of acceptable versions, or ANY (``If-Match: *``)
ANY = None


# ----------------------------------------------------------------------------------------------- errors
class RepoError(Exception):
    """Base of the errors of this module."""


class NotFound(RepoError):
    """No such row for this owner (missing, deleted, or another owner's)."""

    def __init__(self, table: str, id: str) -> None:
        super().__init__(f"{table} {id!r} not found")
        self.table, self.id = table, id


class VersionMismatch(RepoError):
    """The row's current version is not one the caller expected (a stale ``If-Match``)."""

    def __init__(self, current: int) -> None:
        super().__init__(f"current version is {current}")
        self.current = current


class LimitReached(RepoError):
    """The owner already has ``limit`` rows of this table."""

    def __init__(self, table: str, limit: int) -> None:
        super().__init__(f"{table}: limit of {limit} reached")
        self.table, self.limit = table, limit


class InUse(RepoError):
    """The vehicle is a member of these fleets (ids, oldest first)."""

    def __init__(self, fleets: list[str]) -> None:
        super().__init__(f"used by fleets {', '.join(fleets)}")
        self.fleets = fleets


class MissingMembers(RepoError):
    """Saved-vehicle members that do not exist for this owner: (index in the request, id)."""

    def __init__(self, missing: list[tuple[int, str]]) -> None:
        super().__init__(", ".join(f"#{i} {v}" for i, v in missing))
        self.missing = missing


# ----------------------------------------------------------------------------------------------- values
@dataclass(frozen=True)
class StoredVehicle:
    id: str
    title: str
    kind: str
    body: str  # JSON text as stored (validated by the caller before any use)
    version: int
    created_at: datetime
    updated_at: datetime


@dataclass(frozen=True)
class Member:
    """One fleet member: exactly one of ``vehicle_id`` (a saved vehicle) and ``preset_id``."""

    vehicle_id: str | None
    preset_id: str | None


@dataclass(frozen=True)
class StoredFleet:
    id: str
    title: str
    members: tuple[Member, ...]  # in order
    version: int
    created_at: datetime
    updated_at: datetime


@dataclass(frozen=True)
class Page:
    """One page of a keyset listing and whether rows follow it."""

    rows: list
    more: bool


def utcnow() -> datetime:
    return datetime.now(UTC)


def as_utc(value: datetime) -> datetime:
    """SQLite gives timestamps back without a zone; they were written in UTC."""
    return value.replace(tzinfo=UTC) if value.tzinfo is None else value.astimezone(UTC)


def _vehicle(row: VehicleRow) -> StoredVehicle:
    return StoredVehicle(
        row.id, row.title, row.kind, row.body, row.version, as_utc(row.created_at), as_utc(row.updated_at)
    )


def _check_version(current: int, expected: frozenset[int] | None) -> None:
    if expected is not ANY and current not in expected:
        raise VersionMismatch(current)


def _keyset(stmt: Select, table, after: tuple[datetime, str] | None, limit: int) -> Select:
    if after is not None:
        at, last_id = after
        stmt = stmt.where(or_(table.created_at > at, and_(table.created_at == at, table.id > last_id)))
    return stmt.order_by(table.created_at, table.id).limit(limit + 1)


def _count(session: Session, table, owner: str) -> int:
    return session.scalar(select(func.count()).select_from(table).where(table.owner == owner)) or 0


# --------------------------------------------------------------------------------------------- vehicles
def insert_vehicle(db: Database, owner: str, id: str, *, title: str, kind: str, body: str, max_count: int):
    """Store a new vehicle at version 1. Raises :class:`LimitReached` when the owner has ``max_count``."""
    with db.write(owner) as session:
        if _count(session, VehicleRow, owner) >= max_count:
            raise LimitReached("vehicles", max_count)
        now = utcnow()
        row = VehicleRow(
            id=id, owner=owner, title=title, kind=kind, body=body, version=1, created_at=now, updated_at=now
        )
        session.add(row)
        session.flush()
        return _vehicle(row)


def get_vehicle(db: Database, owner: str, id: str) -> StoredVehicle:
    with db.read() as session:
        row = session.scalar(select(VehicleRow).where(VehicleRow.id == id, VehicleRow.owner == owner))
        if row is None:
            raise NotFound("vehicle", id)
        return _vehicle(row)


def update_vehicle(
    db: Database, owner: str, id: str, *, expected: frozenset[int] | None, title: str, kind: str, body: str
) -> StoredVehicle:
    """Replace a vehicle if its version is one of ``expected`` (or ANY); the version goes up by one."""
    with db.write(owner) as session:
        current = session.scalar(select(VehicleRow.version).where(VehicleRow.id == id, VehicleRow.owner == owner))
        if current is None:
            raise NotFound("vehicle", id)
        _check_version(current, expected)
        done = session.execute(
            update(VehicleRow)
            .where(VehicleRow.id == id, VehicleRow.owner == owner, VehicleRow.version == current)
            .values(title=title, kind=kind, body=body, version=current + 1, updated_at=utcnow())
            .execution_options(synchronize_session=False)
        )
        if done.rowcount != 1:  # cannot happen under the owner lock; refuse rather than guess
            raise VersionMismatch(current)
        row = session.scalar(select(VehicleRow).where(VehicleRow.id == id).execution_options(populate_existing=True))
        assert row is not None
        return _vehicle(row)


def delete_vehicle(db: Database, owner: str, id: str, *, expected: frozenset[int] | None) -> None:
    """Delete a vehicle; :class:`InUse` when a fleet has it as a member."""
    with db.write(owner) as session:
        current = session.scalar(select(VehicleRow.version).where(VehicleRow.id == id, VehicleRow.owner == owner))
        if current is None:
            raise NotFound("vehicle", id)
        _check_version(current, expected)
        fleets = session.scalars(
            select(FleetRow.id)
            .join(FleetMemberRow, FleetMemberRow.fleet_id == FleetRow.id)
            .where(FleetMemberRow.vehicle_id == id)
            .group_by(FleetRow.id, FleetRow.created_at)
            .order_by(FleetRow.created_at, FleetRow.id)
        ).all()
        if fleets:
            raise InUse(list(fleets))
        session.execute(delete(VehicleRow).where(VehicleRow.id == id, VehicleRow.owner == owner))


def list_vehicles(db: Database, owner: str, *, after: tuple[datetime, str] | None, limit: int) -> Page:
    """The owner's vehicles in (created_at, id) order after the cursor position ``after``."""
    with db.read() as session:
        rows = session.scalars(_keyset(select(VehicleRow).where(VehicleRow.owner == owner), VehicleRow, after, limit))
        found = [_vehicle(r) for r in rows]
    return Page(found[:limit], len(found) > limit)


# ----------------------------------------------------------------------------------------------- fleets
def _members(session: Session, fleet_ids: Sequence[str]) -> dict[str, tuple[Member, ...]]:
    out: dict[str, list[Member]] = {f: [] for f in fleet_ids}
    rows = session.execute(
        select(FleetMemberRow.fleet_id, FleetMemberRow.vehicle_id, FleetMemberRow.preset_id)
        .where(FleetMemberRow.fleet_id.in_(fleet_ids))
        .order_by(FleetMemberRow.fleet_id, FleetMemberRow.position)
    )
    for fleet_id, vehicle_id, preset_id in rows:
        out[fleet_id].append(Member(vehicle_id, preset_id))
    return {f: tuple(m) for f, m in out.items()}


def _fleet(row: FleetRow, members: tuple[Member, ...]) -> StoredFleet:
    return StoredFleet(row.id, row.title, members, row.version, as_utc(row.created_at), as_utc(row.updated_at))


def _write_members(session: Session, owner: str, fleet_id: str, members: Sequence[Member]) -> None:
    """Check that the saved-vehicle members are the owner's, then (re)write the member rows."""
    wanted = {m.vehicle_id for m in members if m.vehicle_id is not None}
    found = set(
        session.scalars(select(VehicleRow.id).where(VehicleRow.owner == owner, VehicleRow.id.in_(wanted)))
        if wanted
        else []
    )
    missing = [
        (i, m.vehicle_id) for i, m in enumerate(members) if m.vehicle_id is not None and m.vehicle_id not in found
    ]
    if missing:
        raise MissingMembers(missing)
    session.execute(delete(FleetMemberRow).where(FleetMemberRow.fleet_id == fleet_id))
    session.add_all(
        FleetMemberRow(fleet_id=fleet_id, position=i, vehicle_id=m.vehicle_id, preset_id=m.preset_id)
        for i, m in enumerate(members)
    )


def insert_fleet(
    db: Database, owner: str, id: str, *, title: str, members: Sequence[Member], max_count: int
) -> StoredFleet:
    with db.write(owner) as session:
        if _count(session, FleetRow, owner) >= max_count:
            raise LimitReached("fleets", max_count)
        now = utcnow()
        row = FleetRow(id=id, owner=owner, title=title, version=1, created_at=now, updated_at=now)
        session.add(row)
        session.flush()
        _write_members(session, owner, id, members)
        return _fleet(row, tuple(members))


def get_fleet(db: Database, owner: str, id: str) -> StoredFleet:
    with db.read() as session:
        row = session.scalar(select(FleetRow).where(FleetRow.id == id, FleetRow.owner == owner))
        if row is None:
            raise NotFound("fleet", id)
        return _fleet(row, _members(session, [id])[id])


def update_fleet(
    db: Database, owner: str, id: str, *, expected: frozenset[int] | None, title: str, members: Sequence[Member]
) -> StoredFleet:
    with db.write(owner) as session:
        current = session.scalar(select(FleetRow.version).where(FleetRow.id == id, FleetRow.owner == owner))
        if current is None:
            raise NotFound("fleet", id)
        _check_version(current, expected)
        done = session.execute(
            update(FleetRow)
            .where(FleetRow.id == id, FleetRow.owner == owner, FleetRow.version == current)
            .values(title=title, version=current + 1, updated_at=utcnow())
            .execution_options(synchronize_session=False)
        )
        if done.rowcount != 1:
            raise VersionMismatch(current)
        _write_members(session, owner, id, members)
        row = session.scalar(select(FleetRow).where(FleetRow.id == id).execution_options(populate_existing=True))
        assert row is not None
        return _fleet(row, tuple(members))


def delete_fleet(db: Database, owner: str, id: str, *, expected: frozenset[int] | None) -> None:
    with db.write(owner) as session:
        current = session.scalar(select(FleetRow.version).where(FleetRow.id == id, FleetRow.owner == owner))
        if current is None:
            raise NotFound("fleet", id)
        _check_version(current, expected)
        session.execute(delete(FleetMemberRow).where(FleetMemberRow.fleet_id == id))
        session.execute(delete(FleetRow).where(FleetRow.id == id, FleetRow.owner == owner))


def get_fleet_with_vehicles(db: Database, owner: str, id: str) -> tuple[StoredFleet, dict[str, StoredVehicle]]:
    """A fleet and its saved-vehicle members, read in one transaction (one consistent state)."""
    with db.read() as session:
        row = session.scalar(select(FleetRow).where(FleetRow.id == id, FleetRow.owner == owner))
        if row is None:
            raise NotFound("fleet", id)
        fleet = _fleet(row, _members(session, [id])[id])
        ids = [m.vehicle_id for m in fleet.members if m.vehicle_id is not None]
        rows = (
            session.scalars(select(VehicleRow).where(VehicleRow.owner == owner, VehicleRow.id.in_(ids))) if ids else []
        )
        return fleet, {r.id: _vehicle(r) for r in rows}


def list_fleets(db: Database, owner: str, *, after: tuple[datetime, str] | None, limit: int) -> Page:
    with db.read() as session:
        rows = list(session.scalars(_keyset(select(FleetRow).where(FleetRow.owner == owner), FleetRow, after, limit)))
        members = _members(session, [r.id for r in rows])
        found = [_fleet(r, members[r.id]) for r in rows]
    return Page(found[:limit], len(found) > limit)
