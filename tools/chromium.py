"""Debian's chromium as Playwright drives it headless, for the browser tests and the app
benchmarks: the executable and its launch flags (no sandbox, GPU, QUIC, first-run page or
background network)."""

CHROMIUM = "/usr/bin/chromium"
LAUNCH_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
