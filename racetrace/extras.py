"""Which optional extras are installed: the check of :mod:`report.extras`, for the commands."""

from report.extras import missing_modules

__all__ = ["missing_modules"]
