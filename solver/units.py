"""Unit constants: the SI value of one unit of the case file, the views and the messages.

Defined here once; the models compute in SI (m, kg, s, rad, N, Pa), the case keys and the views
convert at the edges by multiplying (to SI) or dividing (from SI) by these.
"""

from __future__ import annotations

import math

MM = 1e-3  # m
GRAM = 1e-3  # kg
RPM = math.pi / 30.0  # rad/s (one revolution per minute)
GPA = 1e9  # Pa
PER_GPA = 1e-9  # 1/Pa

__all__ = ["GPA", "GRAM", "MM", "PER_GPA", "RPM"]
