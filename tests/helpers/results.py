"""What the tests check of every result Dataset, written once."""

from __future__ import annotations

from solver.results.variables import VARIABLES


def dynamic_variables_in(ds):
    """The registry's dynamic variables that the result ``ds`` holds, as ``(name, Variable)``. A
    dynamic variable it does not hold must be one left out with a Dataset attribute
    ``<name>_note`` saying why (the friction-torque estimates: "not available: ...")."""
    for name, spec in VARIABLES.items():
        if "dynamic" not in spec.models:
            continue
        if name not in ds:
            assert str(ds.attrs.get(f"{name}_note", "")).startswith("not available"), name
            continue
        yield name, spec
