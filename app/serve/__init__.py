"""Serving the app: the front server and the session processes behind it (one per browser, forked
from a fork server that pre-imports what they share), the secret a session answers, and the log
filters of the server's shutdown."""
