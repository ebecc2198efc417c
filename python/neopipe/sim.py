"""The simulator: worlds of marbles and what the rig's cameras see of them (as `neopipe sim`).

    world = neopipe.sim.world(objects=100, seed=1)          # or neopipe.sim.load_world(path)
    image, truth = neopipe.sim.render(world)                # global camera, realism "rig"
    window, _ = neopipe.sim.render(world, camera="onboard", pose=(250, 250, 30))
"""

import os

import numpy as np

from . import _core

#: The truth's row type: marble id, its centre's projection (u, v) and its contact point's (u0, v0), px.
TRUTH_DTYPE = np.dtype([("id", np.int32), ("u", np.float64), ("v", np.float64), ("u0", np.float64), ("v0", np.float64)])


class World:
    """A world: a W x H mm workspace with identical marbles (`objects`: N x 2 centres, mm)."""

    def __init__(self, core):
        self._core = core

    size = property(lambda self: self._core.size, doc="(width, height), mm.")
    marble_diameter = property(lambda self: self._core.marble_diameter, doc="mm.")
    objects = property(lambda self: self._core.objects, doc="N x 2 marble centres, mm; an object's id is its row.")

    def save(self, path):
        """Write the world as YAML (what `neopipe map --world` and `neopipe nav --world` read)."""
        self._core.save(os.fspath(path))

    def __len__(self):
        return len(self.objects)

    def __repr__(self):
        return f"neopipe.sim.World({len(self)} marbles of {self.marble_diameter} mm in {self.size[0]} x {self.size[1]} mm)"


def world(objects=100, size=(500.0, 500.0), diameter=5.0, min_gap=3.0, seed=1, out=None):
    """Marbles at random without overlap, as `neopipe sim world` (same seed, same world); `out`: also save it."""
    w = World(_core.World.generate(int(objects), (float(size[0]), float(size[1])), float(diameter), float(min_gap),
                                   int(seed)))
    if out is not None:
        w.save(out)
    return w


def load_world(path):
    """Read a world file (FileNotFoundError if it is not there, ValueError naming line and column if malformed)."""
    return World(_core.World.load(os.fspath(path)))


def _as_world(w):
    if isinstance(w, World):
        return w
    if isinstance(w, (str, os.PathLike)):
        return load_world(w)
    raise TypeError(f"world: a neopipe.sim.World or a path, not {type(w).__name__}")


def render(world, camera="global", realism="rig", pose=None, seed=1, resolution=(1280, 960), window=50.0):
    """Render one camera frame of `world` (a World or a world file) as `neopipe sim render` does.

    camera: "global" (above the workspace, `resolution` px) or "onboard" (on the arm, at `pose`
    (x, y, theta: mm, mm, degrees; default the workspace centre), seeing a `window` mm square).
    realism: "ideal", "rig" or "harsh" (docs/simulator.md). seed: the noise's.
    Returns (image, truth): a gray uint8 array, and a structured array of TRUTH_DTYPE with the
    marbles whose centres fall inside the image.
    """
    w = _as_world(world)
    image, rows = _core.render(w._core, camera, realism, None if pose is None else [float(v) for v in pose], int(seed),
                               (int(resolution[0]), int(resolution[1])), float(window))
    return image, np.array(rows, dtype=TRUTH_DTYPE)
