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
:func:`borrowed_record` does the same for every array of a named record (a NamedTuple such as the
model's parameters, and records nested in it), whose other fields must be plain numbers or
tuples of them.
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


def _plain(member) -> bool:
    """True for a record field that numba does not reference-count."""
    if isinstance(member, (types.Number, types.Boolean)):
        return True
    if isinstance(member, types.BaseTuple):
        return all(_plain(t) for t in member.types)
    return False


def _borrowable(member) -> bool:
    """True for a record field :func:`borrowed_record` can take: an array, a plain field, or a
    nested record of them."""
    if isinstance(member, types.Array) or _plain(member):
        return True
    if isinstance(member, types.BaseTuple):
        return all(_borrowable(t) for t in member.types)
    return False


def _borrow_fields(context, builder, record, value):
    """``value`` of tuple type ``record`` with every array in it, at any depth, borrowed."""
    for i, member in enumerate(record.types):
        if isinstance(member, types.Array):
            view = context.make_array(member)(
                context, builder, value=builder.extract_value(value, i)
            )
            view.meminfo = cgutils.get_null_value(view.meminfo.type)
            value = builder.insert_value(value, view._getvalue(), i)
        elif isinstance(member, types.BaseTuple) and not _plain(member):
            inner = _borrow_fields(context, builder, member, builder.extract_value(value, i))
            value = builder.insert_value(value, inner, i)
    return value


@intrinsic
def borrowed_record(typingctx, record):
    """``record`` (a numba tuple or named tuple) with each array field replaced by its borrowed
    view (:func:`borrowed`), also in nested records; every other field must be a number, a
    boolean or a tuple of them."""
    if not isinstance(record, types.BaseTuple) or not _borrowable(record):
        return None

    def codegen(context, builder, signature, args):
        return _borrow_fields(context, builder, record, args[0])

    return record(record), codegen
