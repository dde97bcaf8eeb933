"""How a study chart names its x axis: a case key as an axis title, for the app's Studies panel
and the study report alike."""

from __future__ import annotations

#: Unit suffixes of case keys (``force_N``, ``offset_um``), as an axis title writes them.
KEY_UNITS = {"N": "N", "Nm": "N m", "mm": "mm", "um": "µm", "rpm": "rpm", "deg": "deg"}


def key_label(key: str) -> str:
    """A case key as an axis title: its schema label and unit ("Radial load [N]"); for a key
    without a schema field (``set.preload.force_N``), its last two segments in words and the unit
    its name ends with ("preload force [N]"), else its last segment."""
    from solver import fields_by_key

    field = fields_by_key().get(key)
    if field is not None:
        return f"{field.label} [{field.unit}]" if field.unit else field.label
    *parents, last = key.split(".")
    head, _, unit = last.rpartition("_")
    if head and unit in KEY_UNITS:
        return f"{' '.join([*parents[-1:], head])} [{KEY_UNITS[unit]}]".replace("_", " ")
    return last
