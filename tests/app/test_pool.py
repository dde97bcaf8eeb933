"""Solver slots shared by the sessions (app.services.pool): the cap, the queue, dead holders."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from app.services.pool import SolverPool, default_max_runs


def test_default_cap_is_the_number_of_cores():
    assert default_max_runs() == len(os.sched_getaffinity(0))
    assert SolverPool().max_runs == default_max_runs()
    with pytest.raises(ValueError, match="at least 1"):
        SolverPool(max_runs=-1)


def test_runs_beyond_the_cap_wait_in_order(tmp_path):
    pool = SolverPool(tmp_path, max_runs=1)
    other = SolverPool(tmp_path, max_runs=1)  # another session's pool on the same slots
    a, b, c = pool.enqueue(), other.enqueue(), pool.enqueue()
    assert pool.try_acquire(a) and a.held
    assert not other.try_acquire(b) and b.place == 0  # next, but no free slot
    assert not pool.try_acquire(c) and c.place == 1
    pool.drop(a)
    assert not pool.try_acquire(c)  # b is ahead
    assert other.try_acquire(b)
    other.drop(b)
    assert pool.try_acquire(c) and c.place == 0


def test_a_dead_process_frees_its_slot_and_its_place(tmp_path):
    pool = SolverPool(tmp_path, max_runs=1)
    holder = (
        "import sys, time; from app.services.pool import SolverPool;"
        "p = SolverPool(sys.argv[1], 1); t = p.enqueue(); assert p.try_acquire(t);"
        "w = p.enqueue(); print('held', flush=True); time.sleep(60)"
    )
    proc = subprocess.Popen(
        [sys.executable, "-c", holder, str(tmp_path)], stdout=subprocess.PIPE, text=True
    )
    try:
        assert proc.stdout.readline().strip() == "held"
        mine = pool.enqueue()
        assert not pool.try_acquire(mine) and mine.place == 1  # its waiting ticket is ahead
    finally:
        proc.kill()
        proc.wait()
    assert pool.try_acquire(mine)  # its lock went with it, and its ticket is ignored
