"""A run's first start: the page says whether the solver process loads the compiled kernels or
compiles them (numba's compile events, not a guess), and a cancel while it compiles ends the run at
once with nothing saved. The solver jobs here are stand-ins that report as the real one does."""

from __future__ import annotations

import time

import pytest

from app import runner as runner_module
from app.compile_watch import COMPILING, LOADING, compiling_words, watching_compiles
from app.components.runs import NOTHING_COMPUTED

JOBS = f"""
import time

PREPARING = {runner_module.PREPARING!r}

def loading(case_text, progress, cancel):
    progress(0.0, float("nan"), PREPARING + {LOADING!r})
    while not cancel.is_set():  # loading takes a while; no step yet
        time.sleep(0.05)
    raise SystemExit(0)

def compiling(case_text, progress, cancel):
    progress(0.0, float("nan"), PREPARING + {LOADING!r})
    progress(0.0, float("nan"), PREPARING + {compiling_words(3)!r})
    while True:  # compiling: the cancel event is not looked at
        time.sleep(0.05)
"""


@pytest.fixture
def jobs(tmp_path, monkeypatch):
    (tmp_path / "fake_first_start_jobs.py").write_text(JOBS)
    monkeypatch.syspath_prepend(str(tmp_path))  # spawn children receive the parent's sys.path
    return "fake_first_start_jobs"


def _poll_until(app, condition, timeout_s: float = 60.0) -> None:
    end = time.monotonic() + timeout_s
    while not condition():
        app.runs.poll_runner()
        assert time.monotonic() < end, app.state.status
        time.sleep(0.05)


def test_numba_compiles_are_counted_and_cache_loads_are_not():
    from numba import njit

    @njit
    def twice(x):
        return 2 * x

    seen = []
    with watching_compiles(seen.append, every_s=0.0):
        twice(1.0)
        twice(2.0)  # compiled already: no event
    assert seen == [1]
    with watching_compiles(seen.append):
        twice(3.0)
    assert seen == [1]


def test_the_status_says_loading_when_nothing_is_compiled(app, jobs, monkeypatch):
    monkeypatch.setattr(runner_module, "DYNAMIC_JOB", f"{jobs}:loading")
    app.runs.run()
    try:
        _poll_until(app, lambda: LOADING in app.state.status)
        assert COMPILING not in app.state.status
    finally:
        app.runs.runner.stop_now()
        app.runs.poll_runner()


def test_cancel_while_compiling_ends_the_run_at_once_and_saves_nothing(app, jobs, monkeypatch):
    monkeypatch.setattr(runner_module, "DYNAMIC_JOB", f"{jobs}:compiling")
    app.runs.run()
    _poll_until(app, lambda: COMPILING in app.state.status)
    assert app.state.status == f"running dynamic: {compiling_words(3)}"
    started = time.monotonic()
    app.runs.cancel()
    assert time.monotonic() - started < 5.0
    assert app.state.status == NOTHING_COMPUTED
    assert not app.state.busy and not app.runs.runner.busy
    app.runs.refresh()
    assert app.state.runs == []


def test_the_front_shows_what_is_prepared_until_the_first_session_answers(tmp_path, monkeypatch):
    """While the first session is prepared, a browser opening the page is shown what is being
    prepared (the fork server's words) instead of waiting on a blank page; once the session
    answers, the status says ready."""
    import asyncio
    import json

    from aiohttp.test_utils import make_mocked_request

    from app.access import Access
    from app.serve import preparing
    from app.serve.front import COOKIE, PREPARING_PATH, Front, Session

    status_file = tmp_path / "preparing.txt"
    monkeypatch.setenv(preparing.ENV, str(status_file))
    preparing.say("compiling the solver's kernels (first run only): 12 so far")

    class FakeProcess:
        returncode = None

    async def scenario():
        front = Front(Access("127.0.0.1"), [])
        ready = asyncio.get_running_loop().create_future()

        async def spawn():
            return Session("s1", 40001, "secret", FakeProcess(), ready)

        monkeypatch.setattr(front, "_spawn", spawn)
        page = await front.handle(
            make_mocked_request(
                "GET", "/", headers={"Host": "127.0.0.1:8080", "Accept": "text/html"}
            )
        )
        assert page.status == 200 and "racetrace is getting ready" in page.text
        assert page.cookies[COOKIE].value == "s1"
        status = make_mocked_request(
            "GET", PREPARING_PATH, headers={"Host": "127.0.0.1:8080", "Cookie": f"{COOKIE}=s1"}
        )
        answer = json.loads((await front.handle(status)).text)
        assert answer == {
            "ready": False,
            "failed": "",
            "text": "compiling the solver's kernels (first run only): 12 so far",
        }
        ready.set_result(True)
        assert json.loads((await front.handle(status)).text)["ready"] is True

    asyncio.run(scenario())
