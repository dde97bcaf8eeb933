"""Borrowed array views for the hot numba kernels: no reference counting.

numba counts references to every array through its memory record ("meminfo"), with an atomic
increment and decrement each time a kernel binds an array to a variable, slices it, or passes it to
another kernel. In the dynamic model's right-hand side these atomic updates took about a fifth of
an evaluation (a few thousand per evaluation: the per-ball loop binds the scratch arrays, the
contact records and their slices once per ball and contact).

:func:`borrowed` returns a view of the same memory (same data pointer, shape and strides) whose
memory record is null: numba's reference-count calls on it, and on every slice of it, return
at once.
The view does not keep the memory alive, so it may only be used while the array it was made from
is alive and must not leave the kernel that made it (never returned, stored or given to Python).
:func:`solver.models.dynamic.kernels.rhs_into` makes its views on entry and drops them on return.
"""

from __future__ import annotations

from numba import types
from numba.core import cgutils
from numba.extending import intrinsic


@intrinsic
def borrowed(typingctx, array):
    """View of ``array`` (any numba array) that numba does not reference-count (see module)."""
    if not isinstance(array, types.Array):
        return None

    def codegen(context, builder, signature, args):
        view = context.make_array(array)(context, builder, value=args[0])
        view.meminfo = cgutils.get_null_value(view.meminfo.type)
        return view._getvalue()

    return array(array), codegen
