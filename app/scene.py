"""The bearing scene of :mod:`viz.scene`, under the name the session fork server imports it by
(:mod:`app.services.preload`, to share the import with the sessions)."""

from viz.scene import BearingScene, SceneOptions

__all__ = ["BearingScene", "SceneOptions"]
