"""Bearing elements for the ROSS rotordynamics package (``ross-rotordynamics``, the optional extra
``racetrace[ross]``) from quasi-static bearing-set results (docs/rotordynamics.md).

One ``ross.BearingElement`` per bearing of the set, at the shaft node the user names for it, with
the bearing's radial stiffness at the operating point: from one result, constant coefficients;
from several results of the same set at different inner-ring speeds, coefficients over those
speeds (ROSS's ``frequency`` array, rad/s, which ROSS interpolates at the rotor speed).

Frames: the set's results are in the shaft frame (x along the shaft axis, y and z radial); ROSS
puts the rotor axis along its z and the lateral directions along its x and y, so ROSS (x, y, z) =
racetrace (y, z, x): ``kxx = K[y, y]``, ``kyy = K[z, z]``, ``kxy = K[y, z]``, ``kyx = K[z, y]``
and the axial ``kzz = K[x, x]``, each from the bearing's 5x5 stiffness ``bearing_stiffness``
[N/m] about its ball-centre plane (K = -dF/dq, the sign convention of ROSS's stiffness).

What the element cannot carry: the quasi-static model gives no damping (the coefficients c are 0);
a ``BearingElement`` holds forces against translations only, so each bearing's tilt stiffness and
its force-tilt and axial-radial coupling terms are left out (docs/rotordynamics.md says how much
that is and how to add them). The argument dictionaries (:func:`ross_bearing_arguments`) need no
ROSS; :func:`ross_elements` builds the elements and :func:`write_ross_elements` writes each as the
TOML file that ``ross.BearingElement.load`` reads.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import tomli_w

#: The rows/columns of a bearing's stiffness (results-schema.md, "Bearing sets") that ROSS's
#: lateral x, lateral y and axial z directions take.
ROSS_AXES = {"x": "y", "y": "z", "z": "x"}


class RossExportError(ValueError):
    """Results that cannot give ROSS bearing elements; the message says why and what to do."""


def _as_list(results) -> list:
    if isinstance(results, Sequence) and not isinstance(results, str | bytes):
        return list(results)
    return [results]


def _check(results: list, source: str) -> list[str]:
    """The bearing names of ``results`` (bearing-set Datasets of one set at distinct speeds)."""
    if not results:
        raise RossExportError("no result given: give one bearing-set result or several")
    names = None
    speeds = []
    for index, ds in enumerate(results):
        where = f"{source} {index + 1}" if len(results) > 1 else source
        if "bearing" in ds.dims and "time" in ds.dims:
            raise RossExportError(
                f"{where} is a dynamic run of a bearing set (racetrace simulate): the ROSS "
                "elements take each bearing's stiffness from the quasi-static set model; solve "
                "the same case (racetrace solve CASE --output FILE.nc, or solver.solve(case)) "
                "and export that"
            )
        if "bearing" not in ds.dims or "bearing_stiffness" not in ds:
            raise RossExportError(
                f"{where} is not a bearing-set result (no bearing_stiffness along a bearing "
                "dimension): solve a case with a [set] table (racetrace solve CASE --output "
                "FILE.nc, or solver.solve(case)); a set of one bearing gives one element"
            )
        these = [str(b) for b in ds["bearing"].values]
        if names is None:
            names = these
        elif these != names:
            raise RossExportError(
                f"{where} has the bearings {these}, the first result {names}: give results of "
                "one set (at different speeds)"
            )
        speeds.append(float(ds["inner_ring_speed"].values))
    if len(set(speeds)) != len(speeds):
        raise RossExportError(
            "two results have the same inner-ring speed: give one result per speed (ROSS "
            "interpolates the coefficients over the speeds)"
        )
    return names


def ross_bearing_arguments(results, nodes: Sequence[int], source: str = "result") -> list[dict]:
    """The ``ross.BearingElement`` arguments of each bearing of the set, in the set's order:
    ``n`` (its node), ``kxx``, ``kyy``, ``kxy``, ``kyx``, ``kzz`` [N/m], the damping ``cxx``,
    ``cyy``, ``cxy``, ``cyx``, ``czz`` (0: the quasi-static model has none), ``tag`` (the
    bearing's name) and, from several results, ``frequency`` [rad/s] (their inner-ring speeds,
    ascending) with every coefficient a list over it.

    ``results``: one bearing-set Dataset (``solver.solve`` of a set case) or a sequence of them
    (one set at distinct speeds); ``nodes``: the ROSS shaft node of each bearing. Raises
    :class:`RossExportError` naming what is wrong."""
    results = _as_list(results)
    names = _check(results, source)
    nodes = list(nodes)
    if len(nodes) != len(names) or not all(
        isinstance(n, int | np.integer) and not isinstance(n, bool) and n >= 0 for n in nodes
    ):
        raise RossExportError(
            f"give one ROSS shaft node (an integer >= 0) per bearing: the set has "
            f"{len(names)} ({', '.join(names)}), {len(nodes)} node(s) given ({nodes})"
        )
    results = sorted(results, key=lambda ds: float(ds["inner_ring_speed"].values))
    several = len(results) > 1
    elements = []
    for index, name in enumerate(names):
        stiffness = [
            ds["bearing_stiffness"].isel(bearing=index).to_numpy() for ds in results
        ]  # (dof, dof_) in the order x, y, z, tilt_y, tilt_z
        dof = [str(d) for d in results[0]["dof"].values]

        def entry(row: str, column: str, stiffness=stiffness, dof=dof, name=name):
            i, j = dof.index(ROSS_AXES[row]), dof.index(ROSS_AXES[column])
            values = [float(k[i, j]) for k in stiffness]
            for value in values:
                if not math.isfinite(value):
                    raise RossExportError(f"bearing {name!r}: its stiffness is not finite")
            return values if several else values[0]

        zero = [0.0] * len(results) if several else 0.0
        arguments = {
            "n": int(nodes[index]),
            "kxx": entry("x", "x"),
            "kyy": entry("y", "y"),
            "kxy": entry("x", "y"),
            "kyx": entry("y", "x"),
            "kzz": entry("z", "z"),
            "cxx": zero,
            "cyy": zero,
            "cxy": zero,
            "cyx": zero,
            "czz": zero,
            "tag": name,
        }
        if several:
            arguments["frequency"] = [float(ds["inner_ring_speed"].values) for ds in results]
        elements.append(arguments)
    return elements


def _import_ross():
    try:
        import ross
    except Exception as error:  # noqa: BLE001 - ROSS may fail at import for reasons of its own
        raise RossExportError(
            "ROSS (ross-rotordynamics) cannot be imported here "
            f"({type(error).__name__}: {str(error).splitlines()[0][:200]}): install the extra "
            "with pip install 'racetrace[ross]' (docs/rotordynamics.md names the versions "
            "that work together), or write the elements as TOML files, which need no ROSS"
        ) from None
    return ross


def ross_elements(results, nodes: Sequence[int], source: str = "result") -> list:
    """One ``ross.BearingElement`` per bearing of the set (:func:`ross_bearing_arguments`).
    Raises :class:`RossExportError` when ROSS cannot be imported or the results do not fit."""
    ross = _import_ross()
    return [ross.BearingElement(**a) for a in ross_bearing_arguments(results, nodes, source)]


def _file_name(tag: str) -> str:
    safe = "".join(c if c.isalnum() or c in "-_" else "-" for c in tag.strip())
    return f"{safe or 'bearing'}.toml"


def write_ross_elements(results, nodes: Sequence[int], folder, source: str = "result"):
    """Write each bearing's element as ``FOLDER/<bearing name>.toml`` in the layout of
    ``ross.BearingElement.save`` (one table ``BearingElement_<tag>`` of its arguments), which
    ``ross.BearingElement.load(path)`` reads; each file atomically. Needs no ROSS. Returns the
    paths written."""
    from solver import atomic_write

    arguments = ross_bearing_arguments(results, nodes, source)
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    names = [_file_name(a["tag"]) for a in arguments]
    if len(set(names)) != len(names):
        names = [f"{i + 1}-{n}" for i, n in enumerate(names)]
    written = []
    for a, name in zip(arguments, names, strict=True):
        text = tomli_w.dumps({f"BearingElement_{a['tag']}": a})
        path = folder / name
        atomic_write(path, lambda tmp, text=text: Path(tmp).write_text(text, encoding="utf-8"))
        written.append(path)
    return written
