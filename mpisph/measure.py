"""Quantities measured from frames and diagnostics, for validation against references."""

import numpy as np


def semi_axes(frame, dp):
    """Half-extents of a body along x and y: max |coordinate| plus half a spacing."""
    x = frame["x"]
    return np.abs(x[:, 0]).max() + 0.5 * dp, np.abs(x[:, 1]).max() + 0.5 * dp


def surge_front(frame, dp):
    """Largest x reached by the fluid, plus half a spacing (the dam-break toe)."""
    return frame["x"][:, 0].max() + 0.5 * dp


def decay_rate(t, energy):
    """Least-squares slope of ln(energy) against t."""
    return np.polyfit(np.asarray(t), np.log(np.asarray(energy)), 1)[0]


def line_average(frame, points, component, h):
    """Velocity ``component`` at ``points`` (k, dim): Wendland-weighted average of particles within 2h."""
    x, v = frame["x"], frame["v"][:, component]
    out = np.full(len(points), np.nan)
    for k, q in enumerate(np.asarray(points, dtype=float)):
        q_ = np.linalg.norm(x - q, axis=1) / h
        w = np.where(q_ < 2.0, (1.0 - 0.5 * q_) ** 4 * (2.0 * q_ + 1.0), 0.0)
        if w.sum() > 0:
            out[k] = np.sum(w * v) / w.sum()
    return out


def nearest_value(frame, name, point, count=4):
    """Mean of field ``name`` over the ``count`` particles nearest ``point``."""
    d = np.linalg.norm(frame["x"] - np.asarray(point, dtype=float), axis=1)
    return float(np.mean(frame[name][np.argsort(d)[:count]]))
