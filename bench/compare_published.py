"""Print the thesis's published values against the engine's (no assertions; the tests assert).

Run: ``python bench/compare_published.py``. The numbers are the thesis's (see tests/engine/test_published.py
for their sources); Table 17 is repeated here in full to report the error per column.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from engine import Case, LoadCase
from engine.models import rollover_threshold, sweep
from engine.road import max_curve_speed_kmh
from engine.vehicle import PRESETS

BTRAIN, T14 = PRESETS["table16-btrain"], PRESETS["table14-semitrailer"]
SLOPES = [9, 8, 6, 4, 2, 0, -2, -4, -6, -8, -10, -12]
BANKS = [0, 2, 4, 6, 8, 10, 12]
TABLE17 = {  # (trailer angle) -> rows by bank, columns by SLOPES (uphill 9..0, downhill 2..12)
    0: [
        [0.257, 0.240, 0.223, 0.214, 0.208, 0.202, 0.198, 0.194, 0.190, 0.186, 0.181, 0.178],
        [0.278, 0.261, 0.245, 0.235, 0.228, 0.223, 0.218, 0.214, 0.210, 0.206, 0.202, 0.199],
        [0.302, 0.283, 0.265, 0.256, 0.249, 0.244, 0.239, 0.234, 0.230, 0.226, 0.223, 0.219],
        [0.324, 0.305, 0.286, 0.277, 0.270, 0.265, 0.260, 0.256, 0.252, 0.248, 0.244, 0.240],
        [0.349, 0.327, 0.308, 0.299, 0.292, 0.285, 0.281, 0.276, 0.272, 0.268, 0.264, 0.261],
        [0.373, 0.350, 0.330, 0.320, 0.313, 0.307, 0.303, 0.298, 0.294, 0.290, 0.285, 0.281],
        [0.398, 0.372, 0.352, 0.341, 0.334, 0.328, 0.324, 0.319, 0.315, 0.311, 0.307, 0.303],
    ],
    10: [
        [0.258, 0.241, 0.223, 0.214, 0.207, 0.202, 0.197, 0.193, 0.189, 0.185, 0.180, 0.177],
        [0.280, 0.262, 0.245, 0.234, 0.227, 0.222, 0.217, 0.213, 0.209, 0.205, 0.201, 0.198],
        [0.303, 0.283, 0.265, 0.256, 0.249, 0.243, 0.239, 0.233, 0.229, 0.225, 0.222, 0.218],
        [0.326, 0.306, 0.286, 0.276, 0.270, 0.264, 0.259, 0.255, 0.251, 0.247, 0.243, 0.239],
        [0.351, 0.328, 0.308, 0.298, 0.291, 0.285, 0.280, 0.276, 0.271, 0.267, 0.264, 0.260],
        [0.375, 0.351, 0.330, 0.319, 0.312, 0.307, 0.302, 0.297, 0.293, 0.288, 0.284, 0.280],
        [0.401, 0.373, 0.352, 0.341, 0.333, 0.328, 0.323, 0.318, 0.314, 0.310, 0.306, 0.302],
    ],
    20: [
        [0.259, 0.241, 0.222, 0.212, 0.206, 0.200, 0.195, 0.191, 0.187, 0.182, 0.178, 0.175],
        [0.281, 0.262, 0.244, 0.233, 0.226, 0.220, 0.216, 0.211, 0.207, 0.203, 0.199, 0.196],
        [0.304, 0.283, 0.264, 0.254, 0.247, 0.242, 0.236, 0.232, 0.227, 0.224, 0.220, 0.216],
        [0.327, 0.306, 0.285, 0.275, 0.268, 0.262, 0.257, 0.253, 0.249, 0.245, 0.241, 0.236],
        [0.352, 0.328, 0.307, 0.297, 0.290, 0.283, 0.278, 0.274, 0.270, 0.265, 0.262, 0.258],
        [0.377, 0.351, 0.329, 0.318, 0.311, 0.305, 0.300, 0.295, 0.291, 0.286, 0.282, 0.278],
        [0.403, 0.373, 0.351, 0.339, 0.332, 0.326, 0.321, 0.316, 0.312, 0.308, 0.304, 0.300],
    ],
    30: [
        [0.259, 0.240, 0.220, 0.210, 0.203, 0.197, 0.193, 0.188, 0.183, 0.179, 0.176, 0.172],
        [0.281, 0.261, 0.242, 0.231, 0.223, 0.218, 0.213, 0.208, 0.204, 0.200, 0.197, 0.193],
        [0.305, 0.282, 0.262, 0.252, 0.245, 0.239, 0.233, 0.229, 0.225, 0.221, 0.217, 0.213],
        [0.328, 0.305, 0.283, 0.273, 0.265, 0.260, 0.255, 0.250, 0.246, 0.242, 0.238, 0.233],
        [0.353, 0.327, 0.305, 0.295, 0.286, 0.280, 0.275, 0.271, 0.267, 0.263, 0.259, 0.255],
        [0.378, 0.350, 0.327, 0.316, 0.308, 0.302, 0.297, 0.293, 0.287, 0.283, 0.279, 0.275],
        [0.404, 0.372, 0.349, 0.337, 0.329, 0.323, 0.318, 0.313, 0.309, 0.305, 0.301, 0.297],
    ],
}


def row(label, published, ours, unit=""):
    diff = (ours - published) / published * 100
    print(f"| {label:<52} | {published:>8.4g}{unit} | {ours:>8.4f}{unit} | {diff:+6.2f} % |")


def main() -> None:
    b = rollover_threshold(Case(BTRAIN))
    ts = b.stage_values["srt_ts"]
    t14 = rollover_threshold(Case(T14, "2d"))
    print("| quantity (source) | published | ours | difference |\n|---|---|---|---|")
    row("B-train SRT_ts, tires + suspension (Sec. 9.1)", 0.3792, ts)
    row("B-train SRT_3D, full system (Sec. 9.1)", 0.3364, b.srt)
    row("B-train roll theta_3D at the limit [deg] (Fig. 94)", 5.8, b.roll_angle_deg)
    row("B-train rigid SRT t/2h (Sec. 9.2)", 0.451, rollover_threshold(Case(BTRAIN, "rigid")).srt)
    row("Table 14 2D SRT (Sec. 7.2)", 0.376, t14.srt)
    row("Table 14 2D roll [deg] (Fig. 68)", 6.1, t14.roll_angle_deg)
    row("Table 14 2D SRT vs Adams (Sec. 7.1)", 0.374, t14.srt)
    row("Table 14 2D roll vs Adams [deg] (Fig. 66)", 5.75, t14.roll_angle_deg)
    row(
        "Table 14 Rill Eq. 2.20 (2 % from the 2D model, Sec. 7.3)",
        0.376 / 0.98,
        rollover_threshold(Case(T14, "rill")).srt,
    )
    row("B-train rear LLT 0.6, flat (Table 20)", 0.202, rollover_threshold(Case(BTRAIN, rear_llt_limit=0.6)).srt)
    worst = rollover_threshold(Case(BTRAIN, load=LoadCase(lateral_offset_m=0.16))).srt
    row("Table 18 case 3 (worst: d1 = +0.16 m, d2 = 0)", 0.2528, worst)
    best = max(
        rollover_threshold(Case(BTRAIN, load=LoadCase(lateral_offset_m=-0.16, longitudinal_offset_m=d2))).srt
        for d2 in (-1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5)
    )
    row("Table 18 case 1 (best over d2, d1 = -0.16 m)", 0.4485, best)
    ow = rollover_threshold(Case(BTRAIN, load=LoadCase(overweight_percent=1.0))).srt
    row("overweight: loss per 1 % [% of SRT] (Sec. 9.4)", 0.2, (b.srt - ow) / b.srt * 100)
    d1 = rollover_threshold(Case(BTRAIN, load=LoadCase(lateral_offset_m=0.02))).srt
    row("lateral offset: loss per 2 cm [g] (Sec. 9.3)", 0.01, b.srt - d1)
    d3 = rollover_threshold(Case(BTRAIN, load=LoadCase(vertical_offset_m=0.04))).srt
    row("vertical offset: loss per 4 cm [g] (Sec. 9.3)", 0.01, b.srt - d3)
    bb = rollover_threshold(Case(BTRAIN.replace(spring_separation_m=0.96))).srt
    row("spring separation: gain per 1 cm [g] (Fig. 95)", 0.001, bb - b.srt)
    row("Table 18 speed at SRT_3D, R = 80 m [km/h] (Eq. 9.1)", 58.5, float(max_curve_speed_kmh(b.srt, 80)))
    print(
        f"\nLLTf/LLTr at the limit: {b.llt_front / b.llt_rear:.4f} (Kamnik et al.: 0.7); "
        f"chassis constant x = Jr/Jf = {b.parameters['chassis_constant_x']:.4f}"
    )

    print("\nTable 17 (rear LLT 0.6): mean error (ours - thesis) per slope column, each closure of the roll moment")
    for closure in ("chassis-constant", "llt-ratio", "inverse-ratio"):
        res = sweep(
            Case(BTRAIN, rear_llt_limit=0.6),
            {"trailer_angle_deg": [0, 10, 20, 30], "bank_percent": BANKS, "slope_percent": SLOPES},
            chassis_closure=closure,
        )
        ours = res.srt.reshape(4, 7, 12)
        ref = np.array([TABLE17[a] for a in (0, 10, 20, 30)])
        err = ours - ref
        flat = err[0, :, SLOPES.index(0)]
        print(
            f"\n{closure}: flat-road column (psi 0, slope 0) MAE {np.mean(np.abs(flat)):.4f}, "
            f"max {np.max(np.abs(flat)):.4f}; whole table MAE {np.mean(np.abs(err)):.4f}"
        )
        print("| slope % | " + " | ".join(f"{s:+d}" for s in SLOPES) + " |")
        print("|---|" + "---|" * len(SLOPES))
        for k, a in enumerate((0, 10, 20, 30)):
            print(f"| psi {a:2d} deg | " + " | ".join(f"{np.mean(err[k, :, j]):+.4f}" for j in range(12)) + " |")
        print("| MAE | " + " | ".join(f"{np.mean(np.abs(err[:, :, j])):.4f}" for j in range(12)) + " |")
        print(
            f"  psi effect at slope 0, bank 0 (30 deg - 0 deg): ours {ours[3, 0, 5] - ours[0, 0, 5]:+.4f}, "
            f"thesis {ref[3, 0, 5] - ref[0, 0, 5]:+.4f}; downhill 12 % at psi 0: ours "
            f"{ours[0, 0, 11] - ours[0, 0, 5]:+.4f}, thesis {ref[0, 0, 11] - ref[0, 0, 5]:+.4f}"
        )


if __name__ == "__main__":
    main()
