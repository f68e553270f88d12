"""Symmetric tensors stored as their independent components.

A symmetric 3 x 3 tensor (the Cauchy stress, the shear stress) takes 6
numbers per particle instead of 9, in VTK's order xx, yy, zz, xy, yz, xz, so
that ParaView reads the 6-component point array of a frame as a symmetric
tensor. A symmetric dim x dim tensor (the correction matrix B of 000_ Eq. 24)
takes 3 numbers (xx, yy, xy) in 2D and the same 6 as above in 3D.

Component (a, b) of the tensor stored in row ``t[i]`` is
``t[i, component(dim, a, b)]``; hot pair loops spell the indices out.
"""

import numpy as np
from numba import njit

# packed index of component (a, b) of a symmetric 3 x 3 tensor (VTK order)
SYM3 = np.array([[0, 3, 5], [3, 1, 4], [5, 4, 2]])
# the same for a symmetric 2 x 2 tensor (xx, yy, xy)
SYM2 = np.array([[0, 2], [2, 1]])


def size(dim):
    """Number of independent components of a symmetric dim x dim tensor."""
    return dim * (dim + 1) // 2


@njit(inline="always")
def component(dim, a, b):
    """Packed index of component (a, b) of a symmetric dim x dim tensor."""
    return SYM2[a, b] if dim == 2 else SYM3[a, b]


@njit(inline="always")
def unpack_row(t, i, out):
    """out = the 3 x 3 tensor stored packed in row ``t[i]``."""
    for a in range(3):
        for b in range(3):
            out[a, b] = t[i, SYM3[a, b]]


@njit(inline="always")
def times_vector(t, i, dim, v0, v1, v2):
    """The symmetric dim x dim tensor packed in row ``t[i]`` times (v0, v1, v2) (v2 and the third
    component 0 in 2D)."""
    w0 = t[i, component(dim, 0, 0)] * v0 + t[i, component(dim, 0, 1)] * v1
    w1 = t[i, component(dim, 1, 0)] * v0 + t[i, component(dim, 1, 1)] * v1
    w2 = 0.0
    if dim == 3:
        w0 += t[i, component(3, 0, 2)] * v2
        w1 += t[i, component(3, 1, 2)] * v2
        w2 = t[i, component(3, 2, 0)] * v0 + t[i, component(3, 2, 1)] * v1 + t[i, component(3, 2, 2)] * v2
    return w0, w1, w2


@njit(inline="always")
def full_times_vector(T, i, dim, v0, v1, v2):
    """The full dim x dim tensor ``T[i]`` (T of shape (n, dim, dim), not symmetric) times
    (v0, v1, v2) as three scalars (the third 0 in 2D)."""
    if dim == 2:
        return T[i, 0, 0] * v0 + T[i, 0, 1] * v1, T[i, 1, 0] * v0 + T[i, 1, 1] * v1, 0.0
    return (T[i, 0, 0] * v0 + T[i, 0, 1] * v1 + T[i, 0, 2] * v2,
            T[i, 1, 0] * v0 + T[i, 1, 1] * v1 + T[i, 1, 2] * v2,
            T[i, 2, 0] * v0 + T[i, 2, 1] * v1 + T[i, 2, 2] * v2)


@njit(cache=True)
def adjugate(A, out):
    """out = adj A of a 2 x 2 or 3 x 3 matrix A (A adj A = det A I); returns det A. For a
    symmetric A the adjugate is symmetric to the bit (its cofactors are the same products)."""
    if A.shape[0] == 2:
        out[0, 0] = A[1, 1]
        out[0, 1] = -A[0, 1]
        out[1, 0] = -A[1, 0]
        out[1, 1] = A[0, 0]
        return A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]
    for a in range(3):
        a1, a2 = (a + 1) % 3, (a + 2) % 3
        for b in range(3):
            b1, b2 = (b + 1) % 3, (b + 2) % 3
            out[b, a] = A[a1, b1] * A[a2, b2] - A[a1, b2] * A[a2, b1]
    return A[0, 0] * out[0, 0] + A[0, 1] * out[1, 0] + A[0, 2] * out[2, 0]


# A 3 x 3 block as nine scalars by rows, which a pair loop keeps in registers while it sums the
# block (a scratch matrix took a third of implicit_viscosity.viscous_pairs' time); 2D uses the upper
# left 2 x 2.
IDENTITY_BLOCK = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)


@njit(inline="always")
def block_less_outer(b, w, x0, x1, x2):
    """The block b less w x (x) x, each entry b_ab - w x_a x_b."""
    return (b[0] - w * x0 * x0, b[1] - w * x0 * x1, b[2] - w * x0 * x2,
            b[3] - w * x1 * x0, b[4] - w * x1 * x1, b[5] - w * x1 * x2,
            b[6] - w * x2 * x0, b[7] - w * x2 * x1, b[8] - w * x2 * x2)


@njit(inline="always")
def block_plus_diagonal(b, w):
    """The block b plus w I."""
    return (b[0] + w, b[1], b[2], b[3], b[4] + w, b[5], b[6], b[7], b[8] + w)


@njit(inline="always")
def store_scaled_inverse(b, scale, block, adj, out):
    """out = (scale b)^-1 of the block b (nine scalars, ``IDENTITY_BLOCK``) of a dim x dim matrix,
    dim that of ``block`` and ``adj`` (scratch matrices), by its adjugate."""
    dim = block.shape[0]
    for a in range(dim):
        for q in range(dim):
            block[a, q] = b[3 * a + q] * scale
    det = adjugate(block, adj)
    for a in range(dim):
        for b in range(dim):
            out[a, b] = adj[a, b] / det


def packed(full):
    """(n, d, d) symmetric tensors as (n, d (d + 1) / 2) packed rows (the upper triangle)."""
    full = np.asarray(full, dtype=np.float64)
    dim = full.shape[-1]
    table = SYM2 if dim == 2 else SYM3
    out = np.empty(full.shape[:-2] + (size(dim),))
    for a in range(dim):
        for b in range(a, dim):
            out[..., table[a, b]] = full[..., a, b]
    return out


def unpacked(rows, dim):
    """(n, d (d + 1) / 2) packed rows as (n, d, d) symmetric tensors."""
    table = SYM2 if dim == 2 else SYM3
    return np.asarray(rows)[..., table]
