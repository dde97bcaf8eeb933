"""exp and log in plain arithmetic, so that loops calling them vectorise (SIMD lanes).

numba compiles ``math.exp`` and ``math.log`` to calls into the C library, and LLVM does not
vectorise a loop that makes such a call (numba from pip has no vector math library). The
functions here use only additions, multiplications, one division, comparisons and the
reinterpretation of a float64's bits as an int64 and back (:func:`float_bits`,
:func:`bits_float`), all of which vectorise. They are meant for the traction kernels' node loops
(solver.physics.traction); elsewhere ``math`` is as good. The loop must be compiled with numpy's
error model (``error_model="numpy"``): numba's default tests every divisor for zero and raises,
and a loop that may leave early does not vectorise.

Accuracy (tests/unit/physics/test_lanes.py): within 1 unit in the last place of ``math.exp`` on
[-708, 709] and of ``math.log`` on all positive normal and subnormal numbers (about 10 % and 4 %
of the results differ from them, by that unit); against the exact values (long double) at most
1.11 and 0.81 units. Special values: exp gives 0 below -708.39 (where the result would be
subnormal) and inf above 709.78; log gives -inf at 0, NaN below 0, inf at inf; NaN stays NaN.

Methods. exp: x = k ln 2 + r with k the nearest integer to x / ln 2 (found by adding and
subtracting 1.5 * 2^52) and |r| <= ln(2) / 2, ln 2 split into a high part with trailing zero bits
(k ln2_hi exact) and a low part; e^r by its Taylor polynomial of degree 13 (truncation below
1e-17 relative); 2^k built in the exponent bits. log: x = 2^k m with m in [sqrt(2)/2, sqrt(2))
read from the bits, f = m - 1 (exact), s = f / (2 + f), and ln(1 + f) = 2 atanh(s) = f - f^2/2
+ s (f^2/2 + R(s^2)) with R the atanh series 2 s^2 / 3 + 2 s^4 / 5 + ... (11 terms: |s| <=
0.172, truncation below 1e-18), which keeps the large terms exact.
"""

from __future__ import annotations

import math

from llvmlite import ir
from numba import njit, types
from numba.extending import intrinsic


@intrinsic
def float_bits(typingctx, x):
    """The bits of the float64 ``x`` as an int64 (a reinterpretation, no conversion)."""
    if x != types.float64:
        return None

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.IntType(64))

    return types.int64(types.float64), codegen


@intrinsic
def bits_float(typingctx, n):
    """The float64 whose bits are the int64 ``n`` (inverse of :func:`float_bits`)."""
    if n != types.int64:
        return None

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.DoubleType())

    return types.float64(types.int64), codegen


_LOG2_E = 1.4426950408889634  # 1 / ln 2
_LN2_HI = 0.6931471803691238  # ln 2 to 32 significant bits: k * _LN2_HI exact for |k| < 2^21
_LN2_LO = 1.9082149292705877e-10  # ln 2 - _LN2_HI
_ROUND = 6755399441055744.0  # 1.5 * 2^52: x + _ROUND - _ROUND rounds x to an integer
_ROUND_BITS = 0x4338000000000000  # float_bits(_ROUND): the integer sits in the low bits
_EXP_MIN = -708.39  # below: the result would be subnormal; 0 is returned
_EXP_MAX = 709.78  # above: overflow; inf is returned

# 1 / j! for j = 2 .. 13 (Taylor polynomial of e^r)
_E2 = 1.0 / 2.0
_E3 = 1.0 / 6.0
_E4 = 1.0 / 24.0
_E5 = 1.0 / 120.0
_E6 = 1.0 / 720.0
_E7 = 1.0 / 5040.0
_E8 = 1.0 / 40320.0
_E9 = 1.0 / 362880.0
_E10 = 1.0 / 3628800.0
_E11 = 1.0 / 39916800.0
_E12 = 1.0 / 479001600.0
_E13 = 1.0 / 6227020800.0

_SQRT_HALF_BITS = 0x3FE6A09E667F3BCD  # float_bits(sqrt(2) / 2)
_TWO_54 = 18014398509481984.0  # 2^54: scales a subnormal into the normal range
_SMALLEST_NORMAL = 2.2250738585072014e-308
# 2 / (2 j + 1) for j = 1 .. 11 (the atanh series of ln(1 + f) in s^2)
_L1 = 2.0 / 3.0
_L2 = 2.0 / 5.0
_L3 = 2.0 / 7.0
_L4 = 2.0 / 9.0
_L5 = 2.0 / 11.0
_L6 = 2.0 / 13.0
_L7 = 2.0 / 15.0
_L8 = 2.0 / 17.0
_L9 = 2.0 / 19.0
_L10 = 2.0 / 21.0
_L11 = 2.0 / 23.0


@njit(cache=True, inline="always")
def exp_lanes(x):
    """e^x (module docstring: accuracy, special values); vectorises."""
    t = x * _LOG2_E + _ROUND
    k = t - _ROUND
    r = (x - k * _LN2_HI) - k * _LN2_LO
    p = _E12 + r * _E13
    p = _E11 + r * p
    p = _E10 + r * p
    p = _E9 + r * p
    p = _E8 + r * p
    p = _E7 + r * p
    p = _E6 + r * p
    p = _E5 + r * p
    p = _E4 + r * p
    p = _E3 + r * p
    p = _E2 + r * p
    p = 1.0 + r * (1.0 + r * p)
    # 2^k from its exponent bits (k in [-1022, 1023] on the allowed range)
    scale = bits_float((float_bits(t) - _ROUND_BITS + 1023) << 52)
    v = p * scale
    v = 0.0 if x < _EXP_MIN else v
    return math.inf if x > _EXP_MAX else v


@njit(cache=True, inline="always")
def log_lanes(x):
    """ln x (module docstring: accuracy, special values); vectorises."""
    subnormal = x < _SMALLEST_NORMAL
    xs = x * _TWO_54 if subnormal else x
    bits = float_bits(xs)
    k = (bits - _SQRT_HALF_BITS) >> 52  # x = 2^k m, m in [sqrt(2)/2, sqrt(2))
    f = bits_float(bits - (k << 52)) - 1.0
    kf = float(k) - 54.0 if subnormal else float(k)
    s = f / (2.0 + f)
    z = s * s
    r = _L10 + z * _L11
    r = _L9 + z * r
    r = _L8 + z * r
    r = _L7 + z * r
    r = _L6 + z * r
    r = _L5 + z * r
    r = _L4 + z * r
    r = _L3 + z * r
    r = _L2 + z * r
    r = z * (_L1 + z * r)
    half_f2 = 0.5 * f * f
    v = kf * _LN2_HI - ((half_f2 - (s * (half_f2 + r) + kf * _LN2_LO)) - f)
    v = -math.inf if x == 0.0 else v
    v = math.nan if x < 0.0 else v
    return v if x < math.inf else x  # inf, and NaN (no comparison holds)
