"""load -> to_toml -> load, and to_dict -> from_dict, give equal cases (also for random
valid cases)."""

from __future__ import annotations

import math
import tomllib

import tomli_w
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from solver.case import FIELDS, Case, parse_case
from solver.case.schema import OPTIONAL
from solver.catalogue import catalogue


def test_catalogue_cases_round_trip():
    for entry in catalogue().entries:
        case = entry.load()
        text = case.to_toml()
        folder = case.source_dir or None  # where a history file of the case is read from
        assert parse_case(text, "text", folder) == case, entry.name
        assert Case.from_dict(case.to_dict(), folder) == case, entry.name


def test_to_toml_is_readable(valid):
    case = parse_case(tomli_w.dumps(valid))
    text = case.to_toml()
    headers = [line for line in text.splitlines() if line.startswith("[")]
    assert headers == ["[bearing]", "[cage]", "[operating]", "[simulation]"]
    assert "ball_diameter_mm = 7.144" in text
    # estimated cage values are comments (so they follow the bearing when it is edited)
    assert "# pocket_diametral_clearance_mm = " in text
    assert "# [lubricant] not given" in text


def test_estimates_follow_the_documented_rules(valid):
    """Cage estimates of docs/case-format.md: 0.028 D, 0.0055 d_m, 0.5 D, polymer-ring mass."""
    case = parse_case(tomli_w.dumps(valid))
    D, dm = 7.144, 54.0
    assert math.isclose(case.cage.pocket_diametral_clearance_mm, 0.028 * D)
    assert math.isclose(case.cage.guide_diametral_clearance_mm, 0.0055 * dm)
    assert math.isclose(case.cage.guide_land_width_mm, 0.5 * D)
    ring_volume_m3 = math.pi * dm * 1e-3 * (D * 1e-3) * (0.3 * D * 1e-3)
    assert math.isclose(case.cage.mass_g, 1400.0 * ring_volume_m3 * 1e3)
    assert case.cage.pocket_friction == 0.08 and case.cage.guidance == "outer_ring"
    assert case.estimated == {
        "cage.pocket_diametral_clearance_mm",
        "cage.mass_g",
        "cage.guide_diametral_clearance_mm",
        "cage.guide_land_width_mm",
    }
    # no [lubricant]: the schema's default oil, and the case says it was not given
    assert not case.lubricant_given
    for f in FIELDS:
        if f.section == "lubricant":
            value = case
            for part in f.path:
                value = getattr(value, part)
            assert value == (None if f.default is OPTIONAL else f.default), f.key


# ---- random valid cases ------------------------------------------------------------------------
finite = dict(allow_nan=False, allow_infinity=False)
material_table = st.fixed_dictionaries(
    {
        "youngs_modulus_GPa": st.floats(1.0, 500.0, **finite),
        "poisson_ratio": st.floats(0.0, 0.49, **finite),
        "density_kg_m3": st.floats(100.0, 20000.0, **finite),
    }
)


@st.composite
def valid_cases(draw):
    z = draw(st.integers(3, 40))
    d = draw(st.floats(1.0, 40.0, **finite))
    dm = d / math.sin(math.pi / z) * draw(st.floats(1.01, 3.0, **finite))
    fi = draw(st.floats(0.505, 0.6, **finite))
    fo = draw(st.floats(0.505, 0.6, **finite))
    bearing = {
        "ball_count": z,
        "ball_diameter_mm": d,
        "pitch_diameter_mm": dm,
        "inner_groove_radius_ratio": fi,
        "outer_groove_radius_ratio": fo,
    }
    if draw(st.booleans()):
        bearing["designation"] = draw(st.text(max_size=20))
        bearing["provenance"] = draw(
            st.sampled_from(["estimated", "manufacturer", "literature", "measured"])
        )
    a0_len = (fi + fo - 1.0) * d
    if draw(st.booleans()):
        alpha = draw(st.floats(0.0, 59.0, **finite))
        bearing["free_contact_angle_deg"] = alpha
        alpha = math.radians(alpha)
    else:
        pd = draw(st.floats(0.0, 0.95, **finite)) * a0_len
        bearing["diametral_clearance_mm"] = pd
        alpha = math.acos(1.0 - pd / (2.0 * a0_len))
    d_i = dm + 2 * (fi - 0.5) * d * math.cos(alpha) - 2 * fi * d
    d_o = dm - 2 * (fo - 0.5) * d * math.cos(alpha) + 2 * fo * d
    if draw(st.booleans()):
        bearing["inner_shoulder_diameter_mm"] = d_i + draw(st.floats(0.05, 0.95)) * (dm - d_i)
        bearing["outer_shoulder_diameter_mm"] = dm + draw(st.floats(0.05, 0.95)) * (d_o - dm)
    data = {"title": draw(st.text(max_size=30)), "bearing": bearing}
    materials = {}
    for key in ("ball_material", "ring_material"):
        kind = draw(st.sampled_from(["builtin", "inline", "user"]))
        if kind == "builtin":
            bearing[key] = draw(st.sampled_from(["bearing_steel", "silicon_nitride"]))
        elif kind == "inline":
            bearing[key] = draw(material_table)
        else:
            name = draw(
                st.from_regex(r"[a-z][a-z0-9_-]{0,10}", fullmatch=True).filter(
                    lambda n: n not in ("bearing_steel", "silicon_nitride")
                )
            )
            materials[name] = draw(material_table)
            bearing[key] = name
    if materials:
        data["materials"] = materials
    cage = draw(
        st.fixed_dictionaries(
            {},
            optional={
                "guidance": st.sampled_from(["outer_ring", "inner_ring", "ball"]),
                "pocket_diametral_clearance_mm": st.floats(0.01, 1.0, **finite),
                "guide_diametral_clearance_mm": st.floats(0.01, 1.0, **finite),
                "mass_g": st.floats(0.1, 500.0, **finite),
                "pocket_friction": st.floats(0.0, 1.0, **finite),
                "guide_land_width_mm": st.floats(0.1, 20.0, **finite),
            },
        )
    )
    if cage or draw(st.booleans()):
        data["cage"] = cage
    if draw(st.booleans()):
        mu_max = draw(st.floats(0.01, 1.0, **finite))
        data["lubricant"] = {
            "viscosity_Pas": draw(st.floats(1e-4, 1.0, **finite)),
            "pressure_viscosity_per_GPa": draw(st.floats(1.0, 40.0, **finite)),
            "traction": {
                "mu_zero": draw(st.floats(0.0, 1.0)) * mu_max,
                "mu_max": mu_max,
                "slip_at_max_m_s": draw(st.floats(0.01, 10.0, **finite)),
                "mu_infinity": draw(st.floats(0.01, 1.0)) * mu_max,
            },
        }
    operating = {
        "inner_ring_speed_rpm": draw(st.floats(-1e5, 1e5, **finite)),
        "axial_load_N": draw(st.floats(1.0, 1e5, **finite)),
    }
    operating.update(
        draw(
            st.fixed_dictionaries(
                {},
                optional={
                    "outer_ring_speed_rpm": st.floats(-1e5, 1e5, **finite),
                    "radial_load_N": st.floats(0.0, 1e5, **finite),
                    "radial_load_angle_deg": st.floats(-360.0, 360.0, **finite),
                    "misalignment_axis_deg": st.floats(-360.0, 360.0, **finite),
                    "misalignment_frame": st.sampled_from(["space", "ring"]),
                    "moment_axis_deg": st.floats(-360.0, 360.0, **finite),
                },
            )
        )
    )
    tilt = draw(st.sampled_from(["none", "misalignment", "moment"]))
    if tilt == "misalignment":
        operating["misalignment_deg"] = draw(st.floats(-5.0, 5.0, **finite))
    elif tilt == "moment":
        operating["tilting_moment_Nm"] = draw(st.floats(-1e3, 1e3, **finite))
    data["operating"] = operating
    if draw(st.booleans()):
        data["simulation"] = draw(
            st.fixed_dictionaries(
                {},
                optional={
                    "shaft_revolutions": st.floats(0.01, 1000.0, **finite),
                    "samples_per_revolution": st.integers(8, 3600),
                },
            )
        )
    return data


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(valid_cases())
def test_random_valid_cases_round_trip(data):
    text = tomli_w.dumps(data)
    case = parse_case(text)
    assert case.bearing.ball_diameter_mm == data["bearing"]["ball_diameter_mm"]
    assert case.operating.axial_load_N == data["operating"]["axial_load_N"]
    written = case.to_toml()
    tomllib.loads(written)  # valid TOML
    assert parse_case(written) == case
    assert Case.from_dict(case.to_dict()) == case
    assert parse_case(tomli_w.dumps(case.to_dict())) == case
