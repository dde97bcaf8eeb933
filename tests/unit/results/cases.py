"""Case texts shared by the results tests (no catalogue needed)."""

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
