"""The catalog's tables as SQLAlchemy 2 typed ORM classes: saved vehicles, fleets and their members.

``vehicles.body`` and the member lists hold what the owner saved; they are validated again on every read
(``app.catalog.service``), so a damaged row is refused with a problem, never served as it is.

The body is JSON *text* (``Text``), not a ``JSON``/``JSONB`` column, on both databases: the stored bytes are
exactly the canonical JSON the service wrote (JSONB would reorder keys and normalise numbers), and a row whose
text does not parse is reported for that row alone (a ``JSON`` column's driver-side decoder would fail the whole
result set of a listing).

Fleet members are an association table rather than a JSON list: a saved vehicle a fleet uses is a foreign key
with ``ON DELETE RESTRICT``, so the database itself refuses to delete it (the service answers 409 naming the
fleets before it gets there), and "which fleets use this vehicle" is an indexed query.
"""

from __future__ import annotations

from datetime import datetime

from sqlalchemy import CheckConstraint, DateTime, ForeignKey, Index, Integer, MetaData, String, Text
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column

#: length of a saved id: a 4-character prefix (``veh_``, ``flt_``) + 22 url-safe base64 characters (128 bits)
ID_LENGTH = 26
#: the owner column: hex SHA-256 of the bearer key (never the key itself)
OWNER_LENGTH = 64
TITLE_MAX_LENGTH = 200
PRESET_ID_MAX_LENGTH = 100

# deterministic constraint names, so later migrations can refer to them on both databases
NAMING = {
    "ix": "ix_%(table_name)s_%(column_0_N_name)s",
    "uq": "uq_%(table_name)s_%(column_0_N_name)s",
    "ck": "ck_%(table_name)s_%(constraint_name)s",
    "fk": "fk_%(table_name)s_%(column_0_name)s_%(referred_table_name)s",
    "pk": "pk_%(table_name)s",
}


class Base(DeclarativeBase):
    metadata = MetaData(naming_convention=NAMING)


class VehicleRow(Base):
    """A saved vehicle: a full record (``kind='record'``), a builder spec (``kind='spec'``), a combination
    (``kind='combination'``) or a combination builder spec (``kind='combination_spec'``; both since migration 0002)."""

    __tablename__ = "vehicles"

    id: Mapped[str] = mapped_column(String(ID_LENGTH), primary_key=True)
    owner: Mapped[str] = mapped_column(String(OWNER_LENGTH))
    title: Mapped[str] = mapped_column(String(TITLE_MAX_LENGTH))
    kind: Mapped[str] = mapped_column(String(16))
    body: Mapped[str] = mapped_column(Text)
    version: Mapped[int] = mapped_column(Integer)
    created_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    updated_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))

    __table_args__ = (
        CheckConstraint("kind IN ('record', 'spec', 'combination', 'combination_spec')", name="kind"),
        CheckConstraint("version >= 1", name="version"),
        # keyset pagination of one owner's vehicles on (created_at, id)
        Index(None, "owner", "created_at", "id"),
    )


class FleetRow(Base):
    """A named fleet of one owner."""

    __tablename__ = "fleets"

    id: Mapped[str] = mapped_column(String(ID_LENGTH), primary_key=True)
    owner: Mapped[str] = mapped_column(String(OWNER_LENGTH))
    title: Mapped[str] = mapped_column(String(TITLE_MAX_LENGTH))
    version: Mapped[int] = mapped_column(Integer)
    created_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    updated_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))

    __table_args__ = (
        CheckConstraint("version >= 1", name="version"),
        Index(None, "owner", "created_at", "id"),
    )


class FleetMemberRow(Base):
    """Member ``position`` of a fleet: a saved vehicle of the same owner or a preset id (exactly one)."""

    __tablename__ = "fleet_members"

    fleet_id: Mapped[str] = mapped_column(ForeignKey("fleets.id", ondelete="CASCADE"), primary_key=True)
    position: Mapped[int] = mapped_column(Integer, primary_key=True)
    vehicle_id: Mapped[str | None] = mapped_column(ForeignKey("vehicles.id", ondelete="RESTRICT"))
    preset_id: Mapped[str | None] = mapped_column(String(PRESET_ID_MAX_LENGTH))

    __table_args__ = (
        CheckConstraint("(vehicle_id IS NULL) <> (preset_id IS NULL)", name="one_member"),
        CheckConstraint("position >= 0", name="position"),
        Index(None, "vehicle_id"),
    )
