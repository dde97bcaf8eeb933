"""Case texts shared by the tests (no catalogue needed)."""

SPINDLE = """
title = "7008C-class hybrid spindle bearing, combined load"
[bearing]
designation = "7008C-class hybrid"
provenance = "estimated"
ball_count = 18
ball_diameter_mm = 7.144
pitch_diameter_mm = 54.0
inner_groove_radius_ratio = 0.54
outer_groove_radius_ratio = 0.53
free_contact_angle_deg = 15.0
inner_shoulder_diameter_mm = 49.0
outer_shoulder_diameter_mm = 59.0
ball_material = "silicon_nitride"
ring_material = "bearing_steel"
[operating]
inner_ring_speed_rpm = 20000.0
axial_load_N = 500.0
radial_load_N = 300.0
"""

LUBRICANT = """
[lubricant]
viscosity_Pas = 0.01
pressure_viscosity_per_GPa = 20.0
"""

DEEP_GROOVE_RADIAL = """
title = "deep groove, radial load"
[bearing]
designation = "209-class"
provenance = "estimated"
ball_count = 9
ball_diameter_mm = 12.7
pitch_diameter_mm = 65.0
inner_groove_radius_ratio = 0.52
outer_groove_radius_ratio = 0.52
diametral_clearance_mm = 0.015
ball_material = "bearing_steel"
ring_material = "bearing_steel"
[operating]
inner_ring_speed_rpm = 6000.0
radial_load_N = 2000.0
"""

# The example of the case-format contract with the shoulder diameters the contract gives (45.9 /
# 62.2 mm, see "About the contract's example lands" in docs/case-format.md): these lands do not rise
# above the 7008C grooves, so the case loads with warnings.
CONTRACT_EXAMPLE = """
title = "7008C-class hybrid spindle bearing, combined load"

[bearing]
designation = "7008C-class hybrid"
provenance = "estimated"
ball_count = 18
ball_diameter_mm = 7.144
pitch_diameter_mm = 54.0
inner_groove_radius_ratio = 0.54
outer_groove_radius_ratio = 0.53
free_contact_angle_deg = 15.0
inner_shoulder_diameter_mm = 45.9
outer_shoulder_diameter_mm = 62.2
ball_material = "silicon_nitride"
ring_material = "bearing_steel"

[materials.my_steel]
youngs_modulus_GPa = 208.0
poisson_ratio = 0.3
density_kg_m3 = 7800.0

[cage]
guidance = "outer_ring"
pocket_diametral_clearance_mm = 0.20
guide_diametral_clearance_mm = 0.30
mass_g = 6.0

[lubricant]
viscosity_Pas = 0.01
pressure_viscosity_per_GPa = 20.0
traction = { mu_zero = 0.0, mu_max = 0.05, slip_at_max_m_s = 1.0, mu_infinity = 0.036 }

[operating]
inner_ring_speed_rpm = 20000.0
outer_ring_speed_rpm = 0.0
axial_load_N = 500.0
radial_load_N = 300.0
radial_load_angle_deg = 0.0
misalignment_deg = 0.0
misalignment_axis_deg = 90.0
misalignment_frame = "space"

[simulation]
shaft_revolutions = 10.0
samples_per_revolution = 180
"""
