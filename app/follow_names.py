"""Names that the front (:mod:`app.serve.follow`) and the session's follow component
(:mod:`app.components.follow`) share: the front's mark on a follower's websocket, the path of the
follow URL's QR code, and the controller trigger a follower's page calls when it has joined."""

FOLLOWER_HEADER = "X-Racetrace-Follower"  # the front's mark on a follower's websocket to a session
QR_NAME = "__racetrace_follow/qr.svg"  # the follow URL's QR code (served by the front)
JOINED = "follow_joined"
