"""A bool that numba types as a plain run-time ``bool``, not as the literal ``True``/``False``.

numba compiles a kernel once per literal value of a constant argument that it is called with
from compiled code. :func:`solver.models.dynamic.kernels.rhs_into` is called with ``observed``
True (outputs) and False (integrator stages); passed on through :func:`runtime_bool`, its body
(``_rhs_borrowed``, the largest kernel of the model) is compiled once for both, and the flag is
tested when it runs (docs/numerics.md, "Compile time").
"""

from __future__ import annotations

from numba import types
from numba.extending import intrinsic


@intrinsic
def runtime_bool(typingctx, value):
    """``value`` (a bool, literal or not) typed as a plain ``bool``."""
    if not isinstance(types.unliteral(value), types.Boolean):
        return None

    def codegen(context, builder, signature, args):
        return args[0]

    return types.boolean(types.unliteral(value)), codegen
