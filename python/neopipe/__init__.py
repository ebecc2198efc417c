"""neopipe: a real-time image-pipeline engine, from Python.

Frames go in as numpy arrays (uint8, gray H x W or BGR H x W x 3 as cv2 gives them) and come out
as blob tables: numpy structured arrays with the columns `neopipe run` writes to its CSV,

    frame, blob, area, cx, cy, x0, y0, w, h, wcx, wcy

(`cx, cy` the mean pixel position, as OpenCV's centroids; `x0, y0, w, h` the bounding box; `wcx,
wcy` weighted by the gray values; the blobs of a frame in raster order of their first pixel).

    import neopipe
    for table in neopipe.run("video.mp4"):          # or images, a directory, or numpy frames
        print(table["frame"][:1], len(table), table["cx"].mean())
    graph = neopipe.Graph.load("examples/marbles.yaml")
    table = graph.process(frame)                    # one frame, read in place (no copy)

Also: read_table / to_pandas (the CLI's tables), Calibration and calibrate, and the simulator,
map-maker and navigator as neopipe.sim, neopipe.map and neopipe.nav.
"""

from ._core import GraphError
from ._engine import Graph, run, BLOB_DTYPE
from ._table import read_table, to_pandas, concat
from ._calib import Calibration, calibrate
from . import sim, map, nav  # noqa: A004  (neopipe.map is the map-maker, as `neopipe map`)

__all__ = [
    "run", "Graph", "GraphError", "BLOB_DTYPE", "read_table", "to_pandas", "concat",
    "Calibration", "calibrate", "sim", "map", "nav",
]
