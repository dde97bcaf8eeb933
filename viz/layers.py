"""Names of the 3-D view's layers, each one shown or hidden as a whole (no VTK import, so that the
page state can use them without a renderer)."""

LAYERS = (
    "inner_ring",
    "outer_ring",
    "balls",
    "cage",
    "tracks",
    "edges",
    "ellipses",
    "traces",
    "labels",
)
