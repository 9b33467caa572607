"""Layer 4: analysis — Grashof class, ranges of rotation, limit positions, time ratio,
transmission angle, coupler curves, synthesis, the Frenet-frame method, energy and power."""
