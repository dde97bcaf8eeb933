"""No drawing into the 3-D scene's canvas before it has a size.

Panel's vtk.js view draws the scene as soon as the scene is synchronised, which in a saved page
happens before the layout gives the canvas its size: those frames go to framebuffers of size
0 x 0, which WebGL rejects, logging a "framebuffer incomplete" warning for each draw call (some
250 per page). The script below, placed in the page before the document is built, makes the
WebGL calls a canvas without a size would reject return at once instead (draws and clears while
the bound framebuffer is incomplete, textures of zero size): what is drawn is the same (nothing,
until Panel draws again once the view is laid out, on its resize), without the warnings.
"""

from __future__ import annotations

#: Runs once, before the Bokeh document is built (on DOMContentLoaded).
DEFER_SCRIPT = """<script type="text/javascript">
(function () {
  var gl = window.WebGL2RenderingContext && WebGL2RenderingContext.prototype;
  if (!gl || gl.__racetraceDeferred) { return; }
  function unsized(context) {
    var canvas = context.canvas;
    return !canvas || !canvas.width || !canvas.height;
  }
  ["drawArrays", "drawArraysInstanced", "drawElements", "drawElementsInstanced", "clear",
   "clearBufferfv", "clearBufferiv", "clearBufferuiv", "clearBufferfi"].forEach(function (name) {
    var call = gl[name];
    if (!call) { return; }
    gl[name] = function () {
      if (unsized(this) &&
          this.checkFramebufferStatus(this.FRAMEBUFFER) !== this.FRAMEBUFFER_COMPLETE) {
        return undefined;
      }
      return call.apply(this, arguments);
    };
  });
  var storage = gl.texStorage2D;
  gl.texStorage2D = function (target, levels, format, width, height) {
    if (!(width > 0) || !(height > 0)) { return undefined; }
    return storage.apply(this, arguments);
  };
  gl.__racetraceDeferred = true;
})();
</script>"""


def with_deferred_render(page: str) -> str:
    """``page`` (a saved Panel document) with :data:`DEFER_SCRIPT` just before ``</body>``."""
    head, found, tail = page.rpartition("</body>")
    if not found:
        return page + DEFER_SCRIPT
    return head + DEFER_SCRIPT + found + tail
