"""Shipped data: catalogue bearings (``bearings/*.toml``) and example cases (``cases/*.toml``).

Read them with ``importlib.resources.files("assets")`` (see :mod:`solver.catalogue`).
"""
