"""Two numba intrinsics of the lane driver (:mod:`rotorlab.integrate._lanes`).

They do not depend on the model, so they live here rather than in the driver template that
:mod:`rotorlab.integrate._codegen` copies per model (this module's source is part of every copy's
cache key, as every module the template imports). Written as intrinsics because numba has no
strided view with a compile-time stride and no atomic add on an array element.
"""

from __future__ import annotations

from numba import types
from numba.extending import intrinsic


def lane_view(lanes: int):
    """The intrinsic ``view(buf, start, n)``: 1-D view of ``buf[start + i * lanes]``, ``i < n``
    (a lane of a lane-interleaved row).

    The stride is the compile-time constant ``lanes * 8`` bytes, so that LLVM's dependence
    analysis sees all accesses of one row as one range (runtime-stride views defeat it). The
    view carries no meminfo: it lives only for one kernel call inside the owning function.
    """

    @intrinsic
    def view(typingctx, buf, start, n):
        if not (isinstance(buf, types.Array) and buf.ndim == 1 and buf.layout == "C"):
            return None
        out_type = types.Array(buf.dtype, 1, "A")

        def codegen(context, builder, sig, args):
            ary = context.make_array(sig.args[0])(context, builder, args[0])
            start_v = context.cast(builder, args[1], sig.args[1], types.intp)
            n_v = context.cast(builder, args[2], sig.args[2], types.intp)
            out = context.make_array(out_type)(context, builder)
            itemsize = context.get_abi_sizeof(context.get_data_type(out_type.dtype))
            context.populate_array(
                out,
                data=builder.gep(ary.data, [start_v]),
                shape=[n_v],
                strides=[context.get_constant(types.intp, lanes * itemsize)],
                itemsize=context.get_constant(types.intp, itemsize),
                meminfo=None,
                parent=None,
            )
            return out._getvalue()

        return out_type(buf, start, n), codegen

    return view


@intrinsic
def fetch_add(typingctx, counter, delta):
    """Atomically add ``delta`` to ``counter[0]`` (int64 array) and return the old value."""
    if not (isinstance(counter, types.Array) and counter.dtype == types.int64):
        return None

    def codegen(context, builder, sig, args):
        ary = context.make_array(sig.args[0])(context, builder, args[0])
        d = context.cast(builder, args[1], sig.args[1], types.int64)
        return builder.atomic_rmw("add", ary.data, d, "monotonic")

    return types.int64(counter, delta), codegen
