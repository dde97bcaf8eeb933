"""Drawing of a bearing result, shared by the browser app and the report (pyvista/VTK, no trame).

Modules without VTK: :mod:`viz.layers` (layer names), :mod:`viz.palette` (colours),
:mod:`viz.raceway` (points on the grooves), :mod:`viz.frames` (per-frame data of a result),
:mod:`viz.tracks` (painted-track fields), :mod:`viz.set_study` (the charts of a bearing-set
study), :mod:`viz.study_axes` (a study chart's x-axis title). With pyvista: :mod:`viz.scene`
(the bearing scene) and
the parts it composes (:mod:`viz.meshes`, :mod:`viz.layout`, :mod:`viz.painted`, :mod:`viz.bodies`,
:mod:`viz.marks`, :mod:`viz.closeup`, :mod:`viz.overlay`, :mod:`viz.camera`).

Reads results Datasets (with the ``solver`` package's readers); never imports the app, the report or
the command line.
"""
