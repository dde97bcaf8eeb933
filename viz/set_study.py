"""What the charts of a bearing-set study show, for the app's Studies panel and the study report
alike: the stiffness units and the list of charts (docs/study-format.md)."""

from __future__ import annotations

#: Translational and tilting stiffness as the set's charts and tables give them: (unit, scale
#: from SI: N/m and N m/rad)
TRANSLATION_UNIT = ("N/µm", 1e-6)
TILT_UNIT = ("N m/mrad", 1e-3)

#: Charts of a bearing-set study (its Dataset has a ``bearing`` dimension, docs/study-format.md):
#: (name, axis title, scale from SI to the axis unit, ((variable, line tag, dashed), ...)). A
#: variable with a ``bearing`` dimension draws one line per bearing (the tag, when given, after
#: its name), one without draws the set's line. The set's tilting stiffness (from the bearings'
#: spread along the shaft) is some hundred times a bearing's own about its plane: two charts.
SET_STUDY_CHART_METRICS = (
    (
        "axial_stiffness",
        f"axial stiffness [{TRANSLATION_UNIT[0]}]",
        TRANSLATION_UNIT[1],
        (("axial_stiffness", "", False), ("bearing_axial_stiffness", "", False)),
    ),
    (
        "radial_stiffness",
        f"radial stiffness [{TRANSLATION_UNIT[0]}]",
        TRANSLATION_UNIT[1],
        (("radial_stiffness", "", False), ("bearing_radial_stiffness", "", False)),
    ),
    (
        "tilt_stiffness",
        f"set tilt stiffness [{TILT_UNIT[0]}]",
        TILT_UNIT[1],
        (("tilt_stiffness", "", False),),
    ),
    (
        "bearing_tilt_stiffness",
        f"bearing tilt stiffness [{TILT_UNIT[0]}]",
        TILT_UNIT[1],
        (("bearing_tilt_stiffness", "", False),),
    ),
    (
        "bearing_load",
        "load carried [N]",
        1.0,
        (("bearing_axial_load", "axial", False), ("bearing_radial_load", "radial", True)),
    ),
    (
        "contact_angle",
        "mean contact angle [deg]",
        1.0,
        (
            ("bearing_inner_contact_angle", "inner", False),
            ("bearing_outer_contact_angle", "outer", True),
        ),
    ),
)
