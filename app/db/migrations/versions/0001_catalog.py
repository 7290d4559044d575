"""catalog: saved vehicles, fleets and fleet members

Revision ID: 0001
Revises:
Create Date: 2026-11-29
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

revision: str = "0001"
down_revision: str | None = None
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None


def upgrade() -> None:
    op.create_table(
        "vehicles",
        sa.Column("id", sa.String(length=26), nullable=False),
        sa.Column("owner", sa.String(length=64), nullable=False),
        sa.Column("title", sa.String(length=200), nullable=False),
        sa.Column("kind", sa.String(length=8), nullable=False),
        sa.Column("body", sa.Text(), nullable=False),
        sa.Column("version", sa.Integer(), nullable=False),
        sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("updated_at", sa.DateTime(timezone=True), nullable=False),
        sa.CheckConstraint("kind IN ('record', 'spec')", name=op.f("ck_vehicles_kind")),
        sa.CheckConstraint("version >= 1", name=op.f("ck_vehicles_version")),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_vehicles")),
    )
    op.create_index(op.f("ix_vehicles_owner_created_at_id"), "vehicles", ["owner", "created_at", "id"])
    op.create_table(
        "fleets",
        sa.Column("id", sa.String(length=26), nullable=False),
        sa.Column("owner", sa.String(length=64), nullable=False),
        sa.Column("title", sa.String(length=200), nullable=False),
        sa.Column("version", sa.Integer(), nullable=False),
        sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("updated_at", sa.DateTime(timezone=True), nullable=False),
        sa.CheckConstraint("version >= 1", name=op.f("ck_fleets_version")),
        sa.PrimaryKeyConstraint("id", name=op.f("pk_fleets")),
    )
    op.create_index(op.f("ix_fleets_owner_created_at_id"), "fleets", ["owner", "created_at", "id"])
    op.create_table(
        "fleet_members",
        sa.Column("fleet_id", sa.String(length=26), nullable=False),
        sa.Column("position", sa.Integer(), nullable=False),
        sa.Column("vehicle_id", sa.String(length=26), nullable=True),
        sa.Column("preset_id", sa.String(length=100), nullable=True),
        sa.CheckConstraint("(vehicle_id IS NULL) <> (preset_id IS NULL)", name=op.f("ck_fleet_members_one_member")),
        sa.CheckConstraint("position >= 0", name=op.f("ck_fleet_members_position")),
        sa.ForeignKeyConstraint(
            ["fleet_id"], ["fleets.id"], name=op.f("fk_fleet_members_fleet_id_fleets"), ondelete="CASCADE"
        ),
        sa.ForeignKeyConstraint(
            ["vehicle_id"], ["vehicles.id"], name=op.f("fk_fleet_members_vehicle_id_vehicles"), ondelete="RESTRICT"
        ),
        sa.PrimaryKeyConstraint("fleet_id", "position", name=op.f("pk_fleet_members")),
    )
    op.create_index(op.f("ix_fleet_members_vehicle_id"), "fleet_members", ["vehicle_id"])


def downgrade() -> None:
    op.drop_index(op.f("ix_fleet_members_vehicle_id"), table_name="fleet_members")
    op.drop_table("fleet_members")
    op.drop_index(op.f("ix_fleets_owner_created_at_id"), table_name="fleets")
    op.drop_table("fleets")
    op.drop_index(op.f("ix_vehicles_owner_created_at_id"), table_name="vehicles")
    op.drop_table("vehicles")
