"""Fixtures for the drawing package's tests: the app tests' analytic result datasets and bearing
(:mod:`tests.app.conftest`, test fixtures that follow results-schema.md)."""

from tests.app.conftest import (  # noqa: F401  (fixtures)
    dynamic_dataset,
    fixture_model,
    geometry,
    qs_dataset,
)
