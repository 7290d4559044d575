"""Force -> deformation laws of the mechanism's components (Table 2; Eqs. 4.1, 4.6, 4.7, 4.13, 4.14, 4.20-4.23).

Every law works elementwise on floats or numpy arrays. Forces in kN, stiffnesses in kN/m (springs) or
kN m/rad (torsion), lengths in m, angles in rad.

Unspecified parameters (the thesis gives no value; chosen once, for every vehicle)
----------------------------------------------------------------------------------
* **Leaf-spring torsion coefficient kst** (joints 5, 21; joint 6 in 2D; Eq. 4.6). Sec. 3.1 models the
  small shear deformation of a flexible member by a torsion spring at its base with k2 >> k1 (Popov,
  1998): the spring's lateral (shear) stiffness is much larger than its vertical rate. We take the
  equivalent lateral stiffness at the spring top, kst / ls^2, as :data:`SHEAR_TO_VERTICAL_RATIO` = 10
  times the vertical rate of the group's two springs (2 kLs_side): ``kst = 10 * 2 kLs_side * ls^2``
  (4540 kN m/rad for the tridem). With it the leaf-spring sway moves the SRT by < 0.1 %; a ratio of 1
  would lower it by ~1.5 %.
* **Fifth-wheel torsion coefficient** (joint 11, Eq. 4.13): the same rule on the fifth-wheel springs,
  ``10 * 2 kf_side * lf^2``.
* **Chassis torsional rigidity G Jr** (Eq. 4.20): the vehicle record's optional
  ``chassis_torsional_stiffness_knm2_per_rad``; when null the chassis between the rear group and the CG
  section is torsionally rigid (theta27 = 0) and the chassis' torsional compliance acts only through the
  front/rear lateral-load-transfer ratio (Kamnik et al.), which is how Ch. 9 uses it.

References
----------
Thesis Table 2 and Sec. 4.1-4.4; Rill (2011); Popov (1998); Hibbeler (2011).
"""

from __future__ import annotations

import math

#: lateral (shear) stiffness of a leaf spring or fifth-wheel spring over its vertical rate (Sec. 3.1, k2 >> k1)
SHEAR_TO_VERTICAL_RATIO = 10.0


def tire_radius(force_kn, start_force_kn, stiffness_kn_per_m, rolling_radius_m):
    """Instantaneous dynamic rolling radius l_i = lr - (F_T - F_start)/kT [m] (Eq. 4.1)."""
    return rolling_radius_m - (force_kn - start_force_kn) / stiffness_kn_per_m


def leaf_spring_height(force_kn, start_force_kn, stiffness_kn_per_m, suspension_height_m):
    """Instantaneous leaf-spring height l_n = ls - (F_LS - F_start)/kLs [m] (Eq. 4.7)."""
    return suspension_height_m - (force_kn - start_force_kn) / stiffness_kn_per_m


def fifth_wheel_height(force_kn, start_force_kn, stiffness_kn_per_m, fifth_wheel_height_m):
    """Instantaneous fifth-wheel spring height l_f = lfw - (F_FW - F_start)/kf [m] (Eq. 4.14)."""
    return fifth_wheel_height_m - (force_kn - start_force_kn) / stiffness_kn_per_m


def torsion_angle(moment_knm, torsion_coefficient_knm_per_rad):
    """Rotation of a torsion spring theta = T / kst [rad] (Eqs. 4.6, 4.13, Table 2).

    ``moment_knm`` is the moment the spring *applies* to the rotating link (the Davies magnitude Tx of the
    joint, base on leg), so the rotation is ``-Tx / kst``; an infinite coefficient gives 0.
    """
    if math.isinf(torsion_coefficient_knm_per_rad):
        return 0.0 * moment_knm
    return -moment_knm / torsion_coefficient_knm_per_rad


def leaf_spring_rate(length_m, leaves, leaf_width_m, leaf_thickness_m, modulus_kn_per_m2):
    """Rate of a multi-leaf spring kLs = 8 Es nl bl tl^3 / (3 l^3) [kN/m] (Table 2, Rill 2006)."""
    return 8.0 * modulus_kn_per_m2 * leaves * leaf_width_m * leaf_thickness_m**3 / (3.0 * length_m**3)


def shear_torsion_coefficient(vertical_rate_side_kn_per_m, height_m, ratio=SHEAR_TO_VERTICAL_RATIO):
    """Base torsion coefficient of a sprung four-bar (leaf springs or fifth wheel) [kN m/rad].

    Only the first leg carries the group's lateral force (the second one is pin-ended), so its base spring
    stands for the lateral stiffness of both sides: ``kst = ratio * (2 k_side) * height^2``.
    """
    return ratio * 2.0 * vertical_rate_side_kn_per_m * height_m**2


def chassis_torque_split(rear_torque_knm, a_m, wheelbase_m, x):
    """Front torque from the rear one for a shaft built in at both ends, Tf = Tr (L - a)/(a x) (Eq. 4.21).

    ``x = Jr/Jf``; Eq. 4.20 (equal twist of the CG section seen from both ends) rearranged.
    """
    return rear_torque_knm * (wheelbase_m - a_m) / (a_m * x)


def chassis_torque_components(front_torque_knm, cos_psi, sin_psi):
    """Components of the front torque at a trailer/trailer angle psi: (Tf cos psi, Tf sin psi) (Eqs. 4.22-4.23).

    Given psi's cosine and sine (floats or arrays): a solve evaluates this 70-odd times at one psi, so its caller
    computes them once (:func:`engine.models.trailer3d._psi_angles`).
    """
    return front_torque_knm * cos_psi, front_torque_knm * sin_psi


def chassis_twist(rear_torque_knm, segment_length_m, torsional_rigidity_knm2):
    """Twist of the chassis section between the rear group and the CG, Tr (L - a)/(G Jr) [rad] (Eq. 4.20).

    ``rear_torque_knm`` is the Davies magnitude Tx27 (rear bolster on chassis); the chassis twists the other
    way. ``None`` rigidity means torsionally rigid (0).
    """
    if torsional_rigidity_knm2 is None:
        return 0.0 * rear_torque_knm
    return -rear_torque_knm * segment_length_m / torsional_rigidity_knm2
