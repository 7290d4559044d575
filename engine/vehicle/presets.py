"""The thesis presets: the vehicles of Tables 14, 15, 16, 22 and 23 as full records.

References
----------
Moreno, G. G. (thesis), Tables 14-16, 22, 23.
"""

from __future__ import annotations

from dataclasses import dataclass

from engine.errors import UnknownPreset
from engine.vehicle.record import Vehicle

# --------------------------------------------------------------------------------------- presets


@dataclass(frozen=True)
class PresetInfo:
    """What a preset is and where the thesis gives it (the models it suits: :func:`engine.models.supported_models`)."""

    title: str
    source: str


_TRI_AXLE_REAR = dict(
    rear_axles=3,
    rear_tires_per_axle=4,
    suspension_stiffness_kn_per_m=1800.0,
    tire_stiffness_kn_per_m=840.0,
    suspension_height_m=0.205,
    rolling_radius_m=0.499,
    spring_separation_m=0.95,
)

# the 1.86 m tracks and the lead unit's tandem under a fifth wheel, shared by Tables 16 and 23
_TANDEM_FRONT_WITH_FIFTH_WHEEL = dict(
    front_track_m=1.86,
    rear_track_m=1.86,
    front_axle_width_m=1.86,
    rear_axle_width_m=1.86,
    front_axles=2,
    front_tires_per_axle=4,
    fifth_wheel_stiffness_kn_per_m=7500.0,
    fifth_wheel_height_m=0.1,
    fifth_wheel_width_m=0.6,
)

PRESETS: dict[str, Vehicle] = {
    # Ch. 7, Table 14: the 2D model of a semi-trailer's tridem group. Its "equivalent" 5400 and 5040 kN/m
    # are 3 axles x 1800 kN/m and 3 axles x 2 tires per side x 840 kN/m.
    "table14-semitrailer": Vehicle(
        weight_kn=250.0,
        rear_track_m=1.86,
        rear_axle_width_m=1.86,
        cg_height_above_chassis_m=1.346,
        **_TRI_AXLE_REAR,
    ),
    # Ch. 8, Table 15: the TruckSim semi-trailer (LLTf = 0.57 LLTr at the limit, as the check states).
    "table15-semitrailer": Vehicle(
        weight_kn=364.147,
        front_track_m=1.815,
        rear_track_m=1.815,
        front_axle_width_m=1.815,
        rear_axle_width_m=1.815,
        front_axles=1,
        rear_axles=3,
        front_tires_per_axle=4,
        rear_tires_per_axle=4,
        suspension_stiffness_kn_per_m=2500.0,
        tire_stiffness_kn_per_m=980.0,
        fifth_wheel_stiffness_kn_per_m=7500.0,
        suspension_height_m=0.205,
        rolling_radius_m=0.51,
        fifth_wheel_height_m=0.1,
        spring_separation_m=0.95,
        fifth_wheel_width_m=0.6,
        cg_height_above_chassis_m=1.285,
        fifth_wheel_to_front_axle_m=0.9,
        wheelbase_m=8.7,
        front_axle_to_cg_m=5.0,
        front_llt_ratio=0.57,
    ),
    # Ch. 9, Table 16: the rear trailer of a B-train.
    "table16-btrain": Vehicle(
        weight_kn=355.22,
        cg_height_above_chassis_m=1.356,
        fifth_wheel_to_front_axle_m=0.15,
        wheelbase_m=4.26,
        front_axle_to_cg_m=3.0,
        front_llt_ratio=0.7,
        **_TRI_AXLE_REAR,
        **_TANDEM_FRONT_WITH_FIFTH_WHEEL,
    ),
    # Appendix B, Table 22: a rigid truck, one steer axle (single tires) and a tandem (LLTf = 0.9 LLTr).
    "table22-truck": Vehicle(
        weight_kn=255.0,
        front_track_m=1.86,
        rear_track_m=1.86,
        front_axle_width_m=1.86,
        rear_axle_width_m=1.86,
        front_axles=1,
        rear_axles=2,
        front_tires_per_axle=2,
        rear_tires_per_axle=4,
        suspension_stiffness_kn_per_m=1800.0,
        tire_stiffness_kn_per_m=840.0,
        suspension_height_m=0.205,
        rolling_radius_m=0.499,
        spring_separation_m=0.95,
        cg_height_above_chassis_m=1.41,
        fifth_wheel_to_front_axle_m=0.0,
        wheelbase_m=7.62,
        front_axle_to_cg_m=5.63,
        front_llt_ratio=0.9,
    ),
    # Appendix C, Table 23: the semi-trailer of a tractor-semitrailer (LLTf = 0.7 LLTr).
    "table23-semitrailer": Vehicle(
        weight_kn=392.13,
        cg_height_above_chassis_m=1.21,
        fifth_wheel_to_front_axle_m=0.2,
        wheelbase_m=8.7,
        front_axle_to_cg_m=5.55,
        front_llt_ratio=0.7,
        **_TRI_AXLE_REAR,
        **_TANDEM_FRONT_WITH_FIFTH_WHEEL,
    ),
}

PRESET_INFO: dict[str, PresetInfo] = {
    "table14-semitrailer": PresetInfo("Semi-trailer tridem group, 2D (Ch. 7)", "Thesis Table 14 (Adams comparison)"),
    "table15-semitrailer": PresetInfo("Semi-trailer, 1 + 3 axles (Ch. 8)", "Thesis Table 15 (TruckSim comparison)"),
    "table16-btrain": PresetInfo("B-train rear trailer, 2 + 3 axles (Ch. 9)", "Thesis Table 16"),
    "table22-truck": PresetInfo("Rigid truck, 1 + 2 axles (App. B)", "Thesis Table 22"),
    "table23-semitrailer": PresetInfo("Semi-trailer, 2 + 3 axles (App. C)", "Thesis Table 23"),
}


def get_preset(preset_id: str) -> Vehicle:
    """The preset vehicle with this id; :class:`UnknownPreset` lists the known ids otherwise."""
    try:
        return PRESETS[preset_id]
    except KeyError:
        raise UnknownPreset(preset_id, sorted(PRESETS)) from None
