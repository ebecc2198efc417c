"""The navigator in the simulated rig, as `neopipe nav`.

    result = neopipe.nav.trials("world.yaml", 100, sigma_map=1.0)
    print(result["reached_goal_rate"], result["ci95"])
"""

import os
import tempfile

from . import _core


def trials(world, trials, *, cost="reliability", sigma_map=None, realism="rig", calibration_cache=None,
           no_calibration_cache=False, sigma_move=0.003, sigma_rot=0.002, seed=1, recovery=True,
           navigator="tracking", descriptions="extended", min_reliability=0.0, window=50.0, threads=0):
    """Run `trials` journeys between random reachable pairs; return `neopipe nav --trials N --json`'s dict.

    world: a world file or neopipe.sim.World. The survey goes through the global camera and its
    calibration (cached in `calibration_cache`, default $NEOPIPE_CACHE_DIR or ~/.cache/neopipe;
    none with no_calibration_cache) unless sigma_map (mm) asks for a Gaussian one. The other
    options are the CLI's (`neopipe nav --help`): the same options and seed give the same
    journeys and outcomes; only "seconds" and "frames_per_second" (wall time) differ from run to
    run. The interpreter lock is released while the journeys run.
    """
    from .sim import World
    with tempfile.TemporaryDirectory(prefix="neopipe-nav-") as scratch:
        if isinstance(world, World):
            path = os.path.join(scratch, "world.yaml")
            world.save(path)
        else:
            path = os.fspath(world)
        return _core.nav_trials(path, int(trials), cost, sigma_map, realism,
                                os.fspath(calibration_cache) if calibration_cache is not None else "",
                                bool(no_calibration_cache), float(sigma_move), float(sigma_rot), int(seed),
                                bool(recovery), navigator, descriptions, float(min_reliability), float(window),
                                int(threads))
