"""The one registry of results variables (results-schema.md): dimensions, units, names, meaning.

Both models fill values into these definitions; nothing else defines a results variable's units or
description. Units are UDUNITS spellings; angles are in degree in every Dataset, everything else SI.
Dimensions are given for the quasi-static model; the dynamic model appends ``time`` (schema order:
per-contact ``(ball, race, time)``, per-ball ``(ball, time)``, rings ``(time)``). ``VARIABLES``
holds the data variables (the summary metrics included), ``COORDINATES`` the coordinates that say
what a result is (operating point, geometry, materials).

Frames: "inertial" = x along the bearing axis (the direction in which the inner ring carries
thrust), y, z radial, origin at the outer ring centre on the plane of the ball centres in the
just-touching state (rings concentric, every ball touching both races at the free contact angle). A
ring's own frame is attached to that ring and coincides with the inertial frame in the just-touching
state at t = 0.
"""

from __future__ import annotations

from dataclasses import dataclass

from .energy import RESIDUAL_LIMIT

DIMENSION_VALUES = {
    "race": ["inner", "outer"],
    "axis": ["x", "y", "z"],
    "tilt_axis": ["y", "z"],
    "quaternion": ["w", "x", "y", "z"],
    "frame": ["inner_ring", "outer_ring"],
    "body": ["ball", "ring"],
    "ball_loss_source": ["rolling", "sliding", "spin", "drag", "cage_pocket"],
    "loss_source": ["rolling", "sliding", "spin", "drag", "cage_pocket", "cage_land", "cage_drag"],
}


@dataclass(frozen=True)
class Variable:
    """One results variable: dimensions (without ``time``), UDUNITS units, long name, description
    (sign and frame), and which models produce it."""

    dims: tuple[str, ...]
    units: str
    long_name: str
    description: str
    models: tuple[str, ...] = ("quasistatic", "dynamic")
    time_dependent: bool = True  # False for the dynamic model's summary metrics

    def dims_for(self, model: str) -> tuple[str, ...]:
        """Dimensions in a Dataset of ``model`` ("quasistatic" or "dynamic")."""
        if model == "dynamic" and self.time_dependent:
            return (*self.dims, "time")
        return self.dims

    def attrs(self) -> dict[str, str]:
        """NetCDF attributes: units, long_name, description."""
        return {"units": self.units, "long_name": self.long_name, "description": self.description}


_C = ("ball", "race")
_B = ("ball",)
_QS = ("quasistatic",)
_DYN = ("dynamic",)

VARIABLES: dict[str, Variable] = {
    # ---- per contact -------------------------------------------------------------------------
    "contact_load": Variable(
        _C,
        "N",
        "contact normal load",
        "normal load Q of the ball-race contact (>= 0; 0 when the contact is open)",
    ),
    "contact_angle": Variable(
        _C,
        "degree",
        "contact angle",
        "angle of the contact line in the ring's meridian plane, from the radial plane; positive "
        "when the outer contact lies on the +x side of the ball centre and the inner contact on "
        "the -x side (thrust carried in +x); may be negative. For an open contact: the angle of "
        "the line between the two groove curvature centres (where the ball would touch if the gap "
        "closed)",
    ),
    "contact_deflection": Variable(
        _C,
        "m",
        "contact elastic approach",
        "Hertz elastic approach delta (>= 0; 0 when the contact is open)",
    ),
    "ellipse_semi_major": Variable(
        _C,
        "m",
        "contact ellipse semi-major axis",
        "Hertz semi-axis a across the groove (0 when open)",
    ),
    "ellipse_semi_minor": Variable(
        _C,
        "m",
        "contact ellipse semi-minor axis",
        "Hertz semi-axis b in the rolling direction (0 when open)",
    ),
    "max_pressure": Variable(
        _C, "Pa", "peak contact pressure", "peak Hertz pressure 3Q/(2 pi a b) (0 when open)"
    ),
    "raceway_azimuth": Variable(
        _C,
        "degree",
        "contact azimuth on the raceway",
        "circumferential position of the contact centre in that ring's own (rotating) frame, "
        "measured from +y towards +z, wrapped to [0, 360)",
    ),
    "raceway_contact_point": Variable(
        (*_C, "axis"),
        "m",
        "contact centre on the raceway",
        "contact centre (mid-plane of the deformed zone) in that ring's own frame (x, y, z)",
    ),
    "ball_latitude": Variable(
        _C,
        "degree",
        "contact latitude on the ball",
        "latitude of the contact centre on the ball, in the ball-fixed frame (z_b = spin axis "
        "direction cos(beta) e_x - sin(beta) e_r at t = 0; see solver.physics.kinematics)",
    ),
    "ball_longitude": Variable(
        _C,
        "degree",
        "contact longitude on the ball",
        "longitude of the contact centre on the ball in the ball-fixed frame, in (-180, 180]; "
        "x_b = sin(beta) e_x + cos(beta) e_r, y_b = e_theta at t = 0",
    ),
    "spin_to_roll": Variable(
        _C,
        "1",
        "spin-to-roll ratio",
        "omega_spin / omega_roll of the ball relative to the ring (physics.md 2.5.7): projections "
        "of the relative angular velocity on the contact normal and on the rolling axis; 0 without "
        "rolling",
    ),
    "sliding_speed": Variable(
        _C,
        "m/s",
        "sliding speed at the contact centre",
        "magnitude of the sliding velocity at the contact centre",
    ),
    "film_thickness": Variable(
        _C,
        "m",
        "central EHL film thickness",
        "Hamrock-Dowson central film thickness (only with a lubricant); the dynamic model "
        "reduces it for inlet shear heating (solver.physics.rheology.inlet_thermal_factor)",
    ),
    "truncation_margin": Variable(
        _C,
        "degree",
        "contact ellipse truncation margin",
        "shoulder angle minus the groove angle of the ellipse edge |alpha| + a/r; negative = the "
        "ellipse is truncated by the shoulder; NaN when no shoulder diameter is given",
    ),
    # ---- per ball ----------------------------------------------------------------------------
    "ball_azimuth": Variable(
        _B,
        "degree",
        "ball azimuth",
        "orbital position psi of the ball centre, inertial, from +y towards +z",
    ),
    "orbital_speed": Variable(
        _B,
        "rad/s",
        "ball orbital speed",
        "orbital (cage) speed omega_c of the ball centre about +x",
    ),
    "ball_center": Variable((*_B, "axis"), "m", "ball centre", "ball centre position, inertial"),
    "ball_angular_velocity": Variable(
        (*_B, "axis"),
        "rad/s",
        "ball angular velocity",
        "absolute angular velocity of the ball, inertial components",
    ),
    "attitude_angle": Variable(
        _B,
        "degree",
        "ball attitude angle",
        "angle beta of the ball's spin axis (relative to the cage) from the bearing axis, in the "
        "meridian plane: spin axis direction cos(beta) e_x - sin(beta) e_r",
    ),
    "ball_spin_speed": Variable(
        _B,
        "rad/s",
        "ball spin speed relative to the cage",
        "omega_R: the ball's angular velocity relative to the cage is omega_R (cos(beta) e_x - "
        "sin(beta) e_r); negative when the inner ring turns forward with the outer ring fixed",
        _QS,
    ),
    "centrifugal_force": Variable(
        _B,
        "N",
        "ball centrifugal force",
        "m r omega_c^2 with the ball's actual orbit radius r",
        _QS,
    ),
    "gyroscopic_moment": Variable(
        _B,
        "N m",
        "ball gyroscopic moment",
        "moment the contacts apply to the ball along e_theta, M_g = -J omega_c omega_R sin(beta) "
        "(rate of change of the ball's angular momentum in the cage frame)",
        _QS,
    ),
    "race_control": Variable(
        _B,
        "1",
        "controlling race",
        "'inner' or 'outer' (Jones criterion, decided per ball), or 'traction' when the ball "
        "speeds come from the traction balance ([simulation] quasistatic_ball_speeds)",
        _QS,
    ),
    "ball_orientation": Variable(
        (*_B, "quaternion"),
        "1",
        "ball orientation",
        "unit quaternion [w, x, y, z] of the ball-fixed frame, inertial",
        _DYN,
    ),
    "cage_pocket_force": Variable(
        _B, "N", "cage pocket force", "magnitude of the ball-pocket contact force", _DYN
    ),
    # ---- rings and cage ------------------------------------------------------------------------
    "inner_ring_offset": Variable(
        ("axis",),
        "m",
        "inner ring displacement",
        "inner ring centre relative to the outer ring, from the just-touching position",
    ),
    "inner_ring_tilt": Variable(
        ("tilt_axis",),
        "degree",
        "inner ring tilt",
        "tilt of the inner ring relative to the outer ring: rotation vector components about y and "
        "z",
    ),
    "inner_ring_moment": Variable(
        ("tilt_axis",),
        "N m",
        "moment on the inner ring",
        "moment applied to the inner ring about its centre: the given tilting moment when the tilt "
        "is solved, otherwise the moment needed to hold the imposed tilt",
        _QS,
    ),
    "cage_speed": Variable(
        (),
        "rad/s",
        "cage speed",
        "cage angular speed about +x (quasi-static: mean of the balls' orbital speeds)",
    ),
    "cage_center": Variable(("axis",), "m", "cage centre", "cage centre, inertial", _DYN),
    "skidding_ratio": Variable(
        (),
        "1",
        "skidding ratio",
        "cage_speed over the rolling cage speed of the sample: (omega_i r_i + omega_o r_o) / (r_i "
        "+ r_o), r = (d_m -+ D cos alpha) / 2 with the mean contact angle of each race's loaded "
        "contacts (solver.results.skidding); 1 rolling, < 1 the cage lags; NaN where the rolling "
        "speed is 0 or a race has no loaded contact",
        _DYN,
    ),
    "instantaneous_cage_slip": Variable(
        (),
        "1",
        "cage slip",
        "1 - skidding_ratio: the fraction by which the cage lags its rolling speed at the sample "
        "(> 0: it lags; solver.results.skidding)",
        _DYN,
    ),
    # ---- the quasi-static start of a dynamic run (solver.models.quasistatic.result) ------------
    "quasistatic_ball_azimuth": Variable(
        _B,
        "degree",
        "quasi-static ball azimuth",
        "ball_azimuth of the quasi-static solution (race control) of the run's operating point, "
        "the dynamic model's start",
        _DYN,
        time_dependent=False,
    ),
    "quasistatic_contact_angle": Variable(
        _C,
        "degree",
        "quasi-static contact angle",
        "contact_angle of the quasi-static solution (race control) of the run's operating point, "
        "the dynamic model's start",
        _DYN,
        time_dependent=False,
    ),
    "quasistatic_contact_load": Variable(
        _C,
        "N",
        "quasi-static contact load",
        "contact_load of the quasi-static solution (race control) of the run's operating point, "
        "the dynamic model's start",
        _DYN,
        time_dependent=False,
    ),
    "quasistatic_cage_speed": Variable(
        (),
        "rad/s",
        "quasi-static cage speed",
        "cage_speed of the quasi-static solution (race control) of the run's operating point, "
        "the dynamic model's start",
        _DYN,
        time_dependent=False,
    ),
    # ---- losses, torque and heat (dynamic model; 0 with traction off) -------------------------
    "contact_heat": Variable(
        _C,
        "W",
        "heat generated in the contact",
        "power dissipated in the ball-race contact: rolling resistance (EHL inlet force and "
        "elastic hysteresis) + traction from sliding + traction from spin",
        _DYN,
    ),
    "ball_power_loss": Variable(
        ("ball", "ball_loss_source"),
        "W",
        "power loss per ball by source",
        "rolling: rolling resistance of both race contacts; sliding and spin: traction power of "
        "both race contacts from the centre slip and from the relative rotation; drag: oil-air "
        "drag on the ball; cage_pocket: dissipated in the ball's pocket contact (friction and "
        "contact damping)",
        _DYN,
    ),
    "power_loss": Variable(
        ("loss_source",),
        "W",
        "bearing power loss by source",
        "ball_power_loss summed over the balls, plus cage_land: dissipated at the cage-guiding "
        "land (hydrodynamic and metal contact), and cage_drag: oil-air drag moment on the "
        "cage's rotation",
        _DYN,
    ),
    "total_power_loss": Variable(
        (), "W", "total power loss", "sum of power_loss over its sources", _DYN
    ),
    "friction_torque": Variable(
        (),
        "N m",
        "friction torque on the inner ring",
        "torque about the inner ring's axis that holds the ring at its imposed speed (positive "
        "when it drives the ring forwards: the bearing's friction torque)",
        _DYN,
    ),
    "drive_power": Variable(
        (),
        "W",
        "drive power",
        "power fed in through the imposed ring rotations; in a steady state its mean equals the "
        "mean total_power_loss (power balance)",
        _DYN,
    ),
    # ---- empirical friction-torque estimates (solver.results.estimates; both models) ----------
    "friction_torque_palmgren": Variable(
        (),
        "N m",
        "Palmgren friction torque estimate",
        "Palmgren's M0 + M1 of the case (applied loads, relative ring speed, oil viscosity at the "
        "inlet temperature, oil-air lubrication): an empirical estimate independent of the "
        "model's contact mechanics. Present only when it can be made; the ``note`` attribute "
        "says what it assumed, and the Dataset attribute friction_torque_palmgren_note why it "
        "is missing",
        time_dependent=False,
    ),
    "friction_torque_skf": Variable(
        (),
        "N m",
        "SKF-model friction torque estimate",
        "the SKF friction model's rolling + sliding torque of the case (open bearing, oil-air "
        "lubrication, no drag term), with the published constants of its bearing series. "
        "Present only when it can be made; the ``note`` attribute says what it assumed, and the "
        "Dataset attribute friction_torque_skf_note why it is missing",
        time_dependent=False,
    ),
    "kinetic_energy": Variable(
        (),
        "J",
        "kinetic energy",
        "kinetic energy of every moving body of the model: the balls' translation and rotation, "
        "the cage's translation, rotation and tilts, the inner ring's translations and tilts "
        "where they are free (the rings' imposed rotations at constant speed are left out)",
        _DYN,
    ),
    "elastic_energy": Variable(
        (),
        "J",
        "elastic energy of the contacts",
        "elastic (Hertz) energy stored in the ball-race contacts, 2/5 Q delta summed over the "
        "loaded contacts (Q the elastic normal load, delta the deflection)",
        _DYN,
    ),
    "load_work": Variable(
        (),
        "J",
        "work of the applied loads",
        "work done since t = 0 by the applied loads on the inner ring (the integral of the force "
        "over the ring's displacement where its translations are free, of the moment over its "
        "tilt under a free tilt) and by gravity on every moving body; positive when the loads "
        "feed energy in",
        _DYN,
    ),
    "energy_balance_residual": Variable(
        (),
        "1",
        "energy balance residual",
        "(mean drive_power - mean total_power_loss + change of load_work - change of "
        "kinetic_energy and of elastic_energy / window length) / mean total_power_loss over the "
        "analysed window, after the first shaft revolution of a run of two or more (time means by "
        "the trapezoidal rule); "
        f"NaN without losses. Beyond {RESIDUAL_LIMIT:g} the result warns: the tolerance is too "
        "loose for the torque, drive power and losses (solver.results.energy)",
        _DYN,
        False,
    ),
    # ---- summary metrics (solver.results.summary; stored in dynamic results) ------------------
    "trajectory_excursion": Variable(
        ("race", "frame"),
        "degree",
        "contact trajectory excursion",
        "peak-to-peak of the mean contact track around the raceway: the contact angle's median in "
        "each of 36 azimuth bins of the ring frame named by ``frame``, max - min over the bins "
        "(loaded contacts in the analysed window; bins with fewer than 5 samples ignored). A "
        "quasi-static result: max - min over its loaded balls",
        _DYN,
        False,
    ),
    "trajectory_excursion_arc": Variable(
        ("race", "frame"),
        "m",
        "contact trajectory excursion (arc)",
        "groove radius times the contact-angle range of trajectory_excursion",
        _DYN,
        False,
    ),
    "trajectory_band_thickness": Variable(
        ("race", "frame"),
        "degree",
        "contact trajectory band thickness",
        "spread of the contact angle at one raceway azimuth of the ring frame named by ``frame``, "
        "across passes and balls: 97.5th minus 2.5th percentile of the residuals from the mean "
        "track (bin medians interpolated between bin centres); 0 for a thin line. A quasi-static "
        "result gives it in steady running (solver.results.steady_track); NaN for a quasi-static "
        "snapshot that no frame holds still",
        _DYN,
        False,
    ),
    "trajectory_band_thickness_arc": Variable(
        ("race", "frame"),
        "m",
        "contact trajectory band thickness (arc)",
        "groove radius times the contact-angle spread of trajectory_band_thickness",
        _DYN,
        False,
    ),
    "ellipse_semi_major_mean": Variable(
        ("race",),
        "m",
        "mean contact ellipse semi-major axis",
        "mean semi-axis a across the groove of the loaded contacts in the analysed window: the "
        "scale against which to read the band thickness (arc)",
        _DYN,
        False,
    ),
    "trajectory_band_width": Variable(
        ("race",),
        "degree",
        "contact trajectory band width",
        "across-groove width of each race's contact track over the analysed window, as a "
        "contact-angle range: max - min of the contact angle of the loaded contacts over all balls "
        "and samples. It mixes excursion and thickness: read trajectory_excursion and "
        "trajectory_band_thickness to tell a line from a band",
        _DYN,
        False,
    ),
    "trajectory_band_width_arc": Variable(
        ("race",),
        "m",
        "contact trajectory band width (arc)",
        "groove radius times the contact-angle range of trajectory_band_width",
        _DYN,
        False,
    ),
    "settling_time": Variable(
        (),
        "s",
        "settling time",
        "start of the first shaft revolution after which every per-revolution mean (over balls "
        "and samples, loaded contacts) of the contact angle and of the spin-to-roll ratio of each "
        "race stays within the settling tolerances of the last revolution's; NaN when the run "
        "does not settle (see settled)",
        _DYN,
        False,
    ),
    "analysis_start_time": Variable(
        (),
        "s",
        "start of the analysed window",
        "time from which the summary metrics are taken (to the end of the run): settling_time "
        "when the run settled, otherwise after the run's first analysis_skip_fraction",
        _DYN,
        False,
    ),
    "settled": Variable(
        (),
        "1",
        "run settled",
        "1 when settling was found with at least 2 shaft revolutions after it, else 0 (the "
        "metrics then cover the last part of an unsettled run; result_warnings says so)",
        _DYN,
        False,
    ),
    # ---- rating life (solver.results.life; stored in both models' results) --------------------
    "basic_load_rating": Variable(
        (),
        "N",
        "basic dynamic load rating C_r (ISO 281)",
        "ISO 281 basic dynamic radial load rating of the bearing from its ball count, ball and "
        "pitch diameters and free contact angle (b_m = 1.3, f_c from Table 1)",
        time_dependent=False,
    ),
    "equivalent_load": Variable(
        (),
        "N",
        "dynamic equivalent load P_r (ISO 281)",
        "ISO 281 dynamic equivalent radial load X F_r + Y F_a of the applied axial and radial "
        "loads (Table 3, single-row angular contact, at the free contact angle)",
        time_dependent=False,
    ),
    "basic_rating_life": Variable(
        (),
        "1",
        "basic rating life L10 (ISO 281)",
        "ISO 281 basic rating life (C_r / P_r)^3, in revolutions of one ring relative to the "
        "other (90 % reliability, no life modification factor)",
        time_dependent=False,
    ),
    "basic_rating_life_time": Variable(
        (),
        "s",
        "basic rating life L10 as time (ISO 281)",
        "basic_rating_life at the result's relative ring speed; inf when the rings do not turn "
        "relative to each other",
        time_dependent=False,
    ),
    "raceway_load_rating": Variable(
        ("race",),
        "N",
        "raceway dynamic load rating Q_c (ISO/TS 16281)",
        "basic dynamic load rating of one ball-raceway contact at the mean contact angle of the "
        "loaded contacts (each contact's own angle enters the life); NaN when none is loaded",
        time_dependent=False,
    ),
    "raceway_equivalent_load": Variable(
        ("race",),
        "N",
        "raceway equivalent rolling-element load Q_e (ISO/TS 16281)",
        "cubic mean (ring rotating relative to the load) or 10/3 mean (ring stationary relative to "
        "it) of the contact loads over every ball (and sample of a dynamic run's analysed window)",
        time_dependent=False,
    ),
    "raceway_rating_life": Variable(
        ("race",),
        "1",
        "raceway rating life (ISO/TS 16281)",
        "life of each raceway, (Q_c / Q_e)^3 with each contact's own Q_c, in revolutions of one "
        "ring relative to the other; inf when no contact of the race is loaded",
        time_dependent=False,
    ),
    "reference_rating_life": Variable(
        (),
        "1",
        "reference rating life L10r (ISO/TS 16281)",
        "ISO/TS 16281 basic reference rating life from the computed contact loads: (L_inner^(-e) "
        "+ L_outer^(-e))^(-1/e), e = 10/9, in revolutions of one ring relative to the other; "
        "clearance, misalignment and the load distribution enter through the loads",
        time_dependent=False,
    ),
    "reference_rating_life_time": Variable(
        (),
        "s",
        "reference rating life L10r as time (ISO/TS 16281)",
        "reference_rating_life at the result's relative ring speed; inf when the rings do not "
        "turn relative to each other",
        time_dependent=False,
    ),
}


#: Coordinates that say what a result is: the operating point and the geometry the views need
#: (written by solver.results.dataset for both models). Scalars, or per race / per body. Angles in
#: degree, the rest SI; strings have units "1".
COORDINATES: dict[str, Variable] = {
    # ---- operating point ---------------------------------------------------------------------
    "inner_ring_speed": Variable(
        (), "rad/s", "inner ring speed", "angular speed of the inner ring about +x"
    ),
    "outer_ring_speed": Variable(
        (), "rad/s", "outer ring speed", "angular speed of the outer ring about +x"
    ),
    "axial_load": Variable(
        (),
        "N",
        "axial load",
        "axial load on the inner ring; positive along +x (presses the inner ring into the balls)",
    ),
    "radial_load": Variable((), "N", "radial load", "radial load on the inner ring (>= 0)"),
    "radial_load_angle": Variable(
        (),
        "degree",
        "radial load azimuth",
        "azimuth of the radial load, inertial, from +y towards +z",
    ),
    "misalignment": Variable(
        (),
        "degree",
        "imposed misalignment",
        "imposed tilt of the inner ring relative to the outer ring (0 when the tilt is solved "
        "under tilting_moment)",
    ),
    "misalignment_axis": Variable(
        (),
        "degree",
        "misalignment axis azimuth",
        "azimuth of the axis the imposed tilt turns about, from +y towards +z, in the frame named "
        "by misalignment_frame (at t = 0 for 'ring')",
    ),
    "misalignment_frame": Variable(
        (),
        "1",
        "misalignment frame",
        "'space': the tilt axis is fixed in space; 'ring': it turns with the inner ring",
    ),
    "tilting_moment": Variable(
        (),
        "N m",
        "tilting moment",
        "moment applied to the inner ring when its tilt is solved; NaN when the tilt is imposed "
        "(misalignment)",
    ),
    "moment_axis": Variable(
        (),
        "degree",
        "tilting moment axis azimuth",
        "azimuth of the tilting moment vector, inertial, from +y towards +z",
    ),
    # ---- geometry ----------------------------------------------------------------------------
    "ball_count": Variable((), "1", "number of balls", "number of balls Z (integer)"),
    "ball_diameter": Variable((), "m", "ball diameter", "ball diameter D"),
    "pitch_diameter": Variable(
        (),
        "m",
        "pitch diameter",
        "diameter d_m of the ball-centre circle in the just-touching state",
    ),
    "free_contact_angle": Variable(
        (),
        "degree",
        "free contact angle",
        "contact angle alpha_0 of the unloaded bearing with the rings concentric",
    ),
    "nominal_contact_angle": Variable(
        (),
        "degree",
        "nominal contact angle",
        "contact angle the ISO 281 basic rating life is rated at: 0 for a radial deep-groove "
        "bearing (a case giving the diametral clearance), else the free contact angle",
    ),
    "groove_radius": Variable(
        ("race",), "m", "groove radius", "raceway groove curvature radius r = f D"
    ),
    "shoulder_diameter": Variable(
        ("race",),
        "m",
        "shoulder diameter",
        "diameter of the land on the thrust-carrying side of the groove; NaN when not given",
    ),
    "groove_bottom_diameter": Variable(
        ("race",),
        "m",
        "groove bottom diameter",
        "diameter of the groove bottom in the ring's own frame",
    ),
    "material": Variable(
        ("body",), "1", "material name", "name of the ball (body 'ball') and ring material"
    ),
    "youngs_modulus": Variable(("body",), "Pa", "Young's modulus", "Young's modulus E"),
    "poisson_ratio": Variable(("body",), "1", "Poisson's ratio", "Poisson's ratio nu"),
    "density": Variable(("body",), "kg m-3", "density", "mass density of the material"),
}


#: Numeric dimension coordinates of derived results (besides ``time``): their values are the
#: dimension's own, e.g. the inner-ring angles of ``solve_over_revolution``.
DIMENSION_COORDINATES: dict[str, Variable] = {
    "ring_angle": Variable(
        ("ring_angle",),
        "degree",
        "inner ring angle",
        "angle the inner ring has turned relative to the outer ring since t = 0, about +x "
        "(dimension of a quasi-static solution over one revolution)",
    ),
}


def variable(name: str) -> Variable:
    """The registered definition of ``name`` (a results variable or a describing coordinate);
    KeyError naming the known names otherwise."""
    try:
        return VARIABLES[name]
    except KeyError:
        pass
    try:
        return COORDINATES[name]
    except KeyError:
        known = ", ".join(sorted(VARIABLES) + sorted(COORDINATES))
        raise KeyError(f"unknown results variable {name!r}; known: {known}") from None


_COORDINATE_NAMES = {
    "race": "race",
    "axis": "Cartesian axis of the frame named by the variable",
    "tilt_axis": "axis of the tilt rotation vector",
    "quaternion": "quaternion component",
    "frame": "ring frame in which a trajectory metric is measured",
    "body": "body the material belongs to",
    "ball_loss_source": "source of a ball's power loss",
    "loss_source": "source of the bearing's power loss",
}


def dimension_coordinate(dim: str) -> tuple:
    """``(dim, labels, attrs)`` of a labelled dimension of DIMENSION_VALUES."""
    import numpy as np

    values = np.array(DIMENSION_VALUES[dim], dtype=object)
    return (dim, values, {"long_name": _COORDINATE_NAMES[dim], "units": "1"})


def coordinates(
    ball_count: int, times=None, *, quaternion: bool = False, losses: bool = False
) -> dict:
    """Dimension coordinates of a results Dataset, each with ``units`` and ``long_name``.

    ``times`` (s) adds the ``time`` coordinate of the dynamic model; ``quaternion`` adds the
    [w, x, y, z] dimension of ``ball_orientation``; ``losses`` the loss-source dimensions of the
    power losses. The ``frame`` dimension comes with the summary metrics, ``body`` with the
    describing coordinates (solver.results.dataset).
    """
    import numpy as np

    coords = {
        "ball": (
            "ball",
            np.arange(ball_count),
            {"long_name": "ball index (ball 0 starts at azimuth 0)", "units": "1"},
        )
    }
    for dim in ("race", "axis", "tilt_axis", "quaternion"):
        if dim == "quaternion" and not quaternion:
            continue
        coords[dim] = dimension_coordinate(dim)
    if losses:
        for dim in ("ball_loss_source", "loss_source"):
            coords[dim] = dimension_coordinate(dim)
    if times is not None:
        coords["time"] = (
            "time",
            np.asarray(times, dtype=np.float64),
            {"long_name": "time", "units": "s"},
        )
    return coords
