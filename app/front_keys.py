"""State keys that the front (:mod:`app.serve.coalesce`) reads in what a session sends a page, and
that the session's components (:mod:`app.components.browser_view`) set."""

#: A state publish carrying this key is urgent: the front sends it past the page's window. The
#: browser-drawn 3-D view counts it up for a frame to be drawn at once (a live control change's
#: first frame), and draws at its next animation frame when it changes.
URGENT_KEY = "rt3d_urgent"
