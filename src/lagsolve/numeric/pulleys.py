"""Where a string's two strands meet at one pulley, and an incline that ends at it (``numeric/scene_shapes.py``
draws them): a block's string up a slope and a weight's straight up from it meet at the pulley on the slope's top
corner, and the slope ends there with a face down from the corner, so that the weight hangs beside the incline,
not inside it."""

from __future__ import annotations

import numpy as np


def meeting(ends: list[np.ndarray], anchors: list[np.ndarray], u1: np.ndarray | None, u2: np.ndarray | None,
            scale: float) -> np.ndarray | None:
    """The fixed point (samples, 2) where two strands of fixed, different directions ``u1``, ``u2`` from their
    ``anchors`` meet beyond where either of the ``ends`` comes (by ``0.08 scale``), or None."""
    if u1 is None or u2 is None or anchors[0].shape[1] != 2 or np.allclose(u1, u2):
        return None
    basis = np.stack([u1, -u2], axis=1)
    if abs(float(np.linalg.det(basis))) < 1e-6:
        return None
    t, _ = np.linalg.solve(basis, anchors[1][0] - anchors[0][0])
    meet = anchors[0][0] + t * u1
    for end, u in ((ends[0], u1), (ends[1], u2)):
        if float(np.min((meet - end) @ u)) < 0.08 * scale:  # an end would pass the pulley
            return None
    return np.broadcast_to(meet, anchors[0].shape).copy()


def corner(band: np.ndarray, pulley: np.ndarray, u: np.ndarray, gravity: np.ndarray,
           scale: float) -> list[np.ndarray] | None:
    """The ground ``band`` (a, b on the surface, then into the material) ended where the strand along it (direction
    ``u``, towards the pulley) meets its ``pulley``, and the face down from that corner along ``gravity`` (a unit
    vector); None when the pulley is not on the band's surface or the strand does not run along it."""
    a, b, into = band[0], band[1], band[3] - band[0]
    e = (b - a) / np.linalg.norm(b - a)
    u = u / np.linalg.norm(u)
    n = into / np.linalg.norm(into)
    if abs(float((pulley - a) @ n)) > 1e-6 * scale or abs(abs(float(u @ e)) - 1.0) > 1e-9:
        return None
    far = a if float((a - pulley) @ u) < float((b - pulley) @ u) else b
    top = pulley - 0.06 * scale * u  # clear of the pulley's rim
    drop = float((far - top) @ gravity)
    if drop <= 0:
        return None
    level = top + drop * gravity
    across = u - (u @ gravity) * gravity
    inward = -across / np.linalg.norm(across)
    depth = float(np.linalg.norm(into))
    slope = np.stack([far, top, top + into, far + into])
    face = np.stack([top, level, level + depth * inward, top + depth * inward])
    return [slope, face]
