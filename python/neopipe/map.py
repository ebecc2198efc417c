"""The map-maker, as `neopipe map`: parkways, trajectories, QOC, routes and their custom maps.

    summary = neopipe.map.make("world.yaml")                 # `neopipe map --world world.yaml --json`
    plan = neopipe.map.route("world.yaml", 3, 41)            # + the best route and its custom map
    print(plan["custom_map_text"])

The dictionaries are `neopipe map ... --json`'s objects, key for key (json.loads of the CLI's output).
"""

import os
import tempfile

from . import _core


def _world_path(world, scratch):
    from .sim import World
    if isinstance(world, World):
        path = os.path.join(scratch, "world.yaml")
        world.save(path)
        return path
    return os.fspath(world)


def make(world=None, *, blobs=None, size=None, window=50.0, margin=None, sigma=None, border_tolerance=0.0,
         descriptions="extended", calib=None, move_error=0.003, rotation_error=0.002, start=None, goal=None,
         cost="ratio", reliable_threshold=0.9):
    """Map a world: what `neopipe map --json` prints, as a dict.

    world: a world file or neopipe.sim.World; or blobs: a blob table with X, Y (`neopipe run
    --calib`), its first frame, on a `size` (W, H) mm workspace. window: the navigator's view side
    a (mm); margin: its corner margin (default 0.05 a); sigma: position error sd (mm; default from
    `calib`'s held-out error, else 1). start, goal: object ids to plan a route between, by `cost`
    ("distance", "reliability", "ratio" or "landmark"); an unreachable goal gives the dict an
    "unreachable" entry, as the CLI's JSON has. Other options as `neopipe map --help` says.
    Raises ValueError for bad options or a world that cannot be mapped, FileNotFoundError for a
    missing file, with the CLI's messages.
    """
    if (world is None) == (blobs is None):
        raise ValueError("give exactly one of world and blobs")
    with tempfile.TemporaryDirectory(prefix="neopipe-map-") as scratch:
        return _core.map_report(
            _world_path(world, scratch) if world is not None else "", os.fspath(blobs) if blobs is not None else "",
            None if size is None else (float(size[0]), float(size[1])), float(window), margin, sigma,
            float(border_tolerance), descriptions, os.fspath(calib) if calib is not None else "", float(move_error),
            float(rotation_error), start, goal, cost, float(reliable_threshold))


def route(world, start, goal, cost="ratio", **options):
    """The best route from object `start` to `goal`: make(world, start=..., goal=..., cost=...).

    The dict has the map's entries and the route's: "path", "costs", "custom_map" (entries) and
    "custom_map_text" (park-kender.md §8's grammar), or "unreachable" (why) when there is none.
    """
    return make(world, start=start, goal=goal, cost=cost, **options)


def custom_map(world, start, goal, cost="ratio", **options):
    """The custom map's text for the route from `start` to `goal`; ValueError if the goal is unreachable."""
    plan = route(world, start, goal, cost=cost, **options)
    if "unreachable" in plan:
        raise ValueError(plan["unreachable"])
    return plan["custom_map_text"]
