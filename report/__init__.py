"""The standalone review report: one self-contained HTML file (Panel), for a run or a study.

``build_report(source, output)`` writes the page (``racetrace report``). It reads results
Datasets only (through ``ds.racetrace`` and the study folder), like every view. Needs the
``report`` extra (Panel, Bokeh, pyvista/VTK): ``pip install -e ".[report]"``.
"""

from .build import REPORT_MODULES, build_report, missing_report_modules

__all__ = ["REPORT_MODULES", "build_report", "missing_report_modules"]
