"""Engineering units for the report: the one place where an SI value becomes the text a reader
sees (MPa/GPa, µm/mm, degree, N·mm, W, rpm, hours).

:func:`shown` takes a value in the SI units the results registry declares (the ``units`` of a
variable or metric, UDUNITS spelling) and returns ``"1.71 GPa"``; :func:`scaled` returns the
number and unit text separately, for a table with a units column.
"""

from __future__ import annotations

import math

#: SI units (as the results registry writes them) -> (scale, unit shown) candidates, in the order
#: tried: the first whose scaled magnitude is at least its threshold is used, else the last.
_ENGINEERING = {
    "Pa": ((1e-9, "GPa", 1.0), (1e-6, "MPa", 0.0)),
    "m": ((1e3, "mm", 1.0), (1e6, "µm", 0.0)),
    "N m": ((1e3, "N·mm", 0.0),),
    "N/m": ((1e-6, "N/µm", 0.0),),
    "rad/s": ((30.0 / math.pi, "rpm", 0.0),),
    "degree": ((1.0, "deg", 0.0),),
    "kg m-3": ((1.0, "kg/m³", 0.0),),
    "1/Pa": ((1e9, "1/GPa", 0.0),),
    "Pa s": ((1e3, "mPa·s", 0.0),),
    "1": ((1.0, "", 0.0),),
}
HOUR = 3600.0  # s


def scaled(value, units: str) -> tuple[float, str]:
    """(value in the engineering unit, that unit's text) for SI ``value`` in ``units``; a unit
    without an engineering form is kept as it is."""
    value = float(value)
    choices = _ENGINEERING.get(units, ((1.0, units, 0.0),))
    for scale, shown_units, threshold in choices:
        if math.isfinite(value) and abs(value * scale) >= threshold:
            return value * scale, shown_units
    scale, shown_units, _ = choices[-1]
    return value * scale, shown_units


def number(value, digits: int = 4) -> str:
    """``value`` to ``digits`` significant digits, thousands grouped with a thin space; "-" when
    it is not a finite number."""
    try:
        value = float(value)
    except (TypeError, ValueError):
        return str(value)
    if not math.isfinite(value):
        return "-" if math.isnan(value) else ("∞" if value > 0 else "-∞")
    if value != 0 and (abs(value) >= 1e7 or abs(value) < 1e-3):
        return f"{value:.{digits - 1}e}"
    if abs(value) >= 10 ** (digits - 1):
        return f"{value:,.0f}".replace(",", "\u2009")
    return f"{value:.{digits}g}"


def shown(value, units: str, digits: int = 4) -> str:
    """SI ``value`` in ``units`` as engineering text: ``shown(1.708e9, "Pa") == "1.708 GPa"``."""
    amount, text = scaled(value, units)
    out = number(amount, digits)
    return f"{out} {text}" if text and out != "-" else out


def hours(seconds, digits: int = 4) -> str:
    """A time in seconds as hours (rating lives)."""
    return f"{number(float(seconds) / HOUR, digits)} h"


def ordinal(n: int) -> str:
    """``1st``, ``2nd``, ``3rd``, ``4th``, ``11th``, ``22nd``."""
    if 10 <= n % 100 <= 20:
        return f"{n}th"
    suffix = {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"
