"""Tests of solver.physics.lanes: exp and log in plain arithmetic against ``math`` and against
extended-precision values (numpy's long double, 64-bit significand on x86-64), and that a loop
calling them vectorises."""

from __future__ import annotations

import math
import platform
import re

import numpy as np
import pytest
from llvmlite import binding as llvm
from numba import njit

from solver.physics.lanes import bits_float, exp_lanes, float_bits, log_lanes


# not cached: the last test reads the machine code of a fresh compilation; numpy's error model
# as in the traction kernels (numba's default tests divisors for zero, which stops vectorisation)
@njit(error_model="numpy")
def _exp_all(x, out):
    for i in range(x.shape[0]):
        out[i] = exp_lanes(x[i])


@njit(error_model="numpy")
def _log_all(x, out):
    for i in range(x.shape[0]):
        out[i] = log_lanes(x[i])


def _ulps(values, reference):
    """|values - reference| in units of the last place of the float64 ``reference``."""
    return np.abs(values - reference) / np.spacing(np.abs(reference))


def _exp_arguments():
    rng = np.random.default_rng(7)
    return np.concatenate(
        [
            rng.uniform(-708.0, 709.0, 40_000),
            rng.uniform(-30.0, 0.0, 40_000),  # the traction curve's exp(-C u)
            rng.uniform(-1e-3, 1e-3, 5_000),
            [0.0, -0.0, 1.0, -1.0, math.log(2.0), -708.0, 709.0],
        ]
    )


def _log_arguments():
    rng = np.random.default_rng(8)
    return np.concatenate(
        [
            np.exp(rng.uniform(-708.0, 709.0, 40_000)),
            rng.uniform(0.5, 2.0, 40_000),  # around 1, where ln x is small
            10.0 ** rng.uniform(-24.0, 4.0, 20_000),  # squared slip speeds [m^2/s^2]
            10.0 ** rng.uniform(-323.0, -308.0, 2_000),  # subnormal
            [1.0, 2.0, 0.5, math.sqrt(2.0), 5e-324, 2.2250738585072014e-308],
            [1.7976931348623157e308],
        ]
    )


@njit
def _bits(x):
    return float_bits(x)


@njit
def _from_bits(n):
    return bits_float(n)


def test_bits_round_trip():
    for x in (0.0, -0.0, 1.0, -2.5, 5e-324, math.inf):
        assert _bits(x) == np.float64(x).view(np.int64)
        assert _from_bits(_bits(x)) == x
        assert math.copysign(1.0, _from_bits(_bits(x))) == math.copysign(1.0, x)


def test_exp_within_one_ulp_of_math():
    x = _exp_arguments()
    out = np.empty_like(x)
    _exp_all(x, out)
    ref = np.array([math.exp(v) for v in x])
    assert np.max(_ulps(out, ref)) <= 1.0
    assert exp_lanes(0.0) == 1.0 and exp_lanes(1.0) == pytest.approx(math.e, rel=3e-16)


def test_log_within_one_ulp_of_math():
    x = _log_arguments()
    out = np.empty_like(x)
    _log_all(x, out)
    ref = np.array([math.log(v) for v in x])
    nonzero = ref != 0.0
    assert np.max(_ulps(out[nonzero], ref[nonzero])) <= 1.0
    assert log_lanes(1.0) == 0.0


@pytest.mark.skipif(
    np.finfo(np.longdouble).nmant < 63, reason="needs an extended-precision long double"
)
def test_exp_and_log_against_extended_precision():
    x = _exp_arguments()
    out = np.empty_like(x)
    _exp_all(x, out)
    exact = np.exp(x.astype(np.longdouble))
    err = np.abs(out.astype(np.longdouble) - exact) / np.spacing(np.abs(exact.astype(np.float64)))
    assert float(np.max(err)) < 1.2
    x = _log_arguments()
    out = np.empty_like(x)
    _log_all(x, out)
    exact = np.log(x.astype(np.longdouble))
    keep = exact != 0.0
    err = np.abs(out.astype(np.longdouble) - exact)[keep] / np.spacing(
        np.abs(exact[keep].astype(np.float64))
    )
    assert float(np.max(err)) < 0.9


def test_special_values():
    assert exp_lanes(-709.0) == 0.0 and exp_lanes(-math.inf) == 0.0
    assert exp_lanes(710.0) == math.inf and exp_lanes(math.inf) == math.inf
    assert math.isnan(exp_lanes(math.nan))
    assert log_lanes(0.0) == -math.inf and log_lanes(-0.0) == -math.inf
    assert math.isnan(log_lanes(-1.0)) and math.isnan(log_lanes(math.nan))
    assert log_lanes(math.inf) == math.inf


def _has_avx2():
    if platform.machine() not in ("x86_64", "AMD64"):
        return False
    return bool(llvm.get_host_cpu_features().get("avx2", False))


@pytest.mark.skipif(not _has_avx2(), reason="checks x86 AVX2/AVX-512 vector registers")
def test_a_loop_of_them_vectorises():
    """The point of the module: LLVM turns the loops above into packed instructions on 4 or 8
    doubles (ymm / zmm registers); with math.exp or math.log they stay scalar."""
    x = np.linspace(0.1, 2.0, 64)
    _exp_all(x, np.empty_like(x))
    _log_all(x, np.empty_like(x))
    for kernel in (_exp_all, _log_all):
        asm = kernel.inspect_asm(kernel.signatures[0])
        assert re.search(r"vmulpd[^\n]*%[yz]mm", asm), "no packed multiplication on ymm/zmm"
