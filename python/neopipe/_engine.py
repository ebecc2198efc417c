"""Graphs and streams of frames: neopipe.Graph and neopipe.run."""

import os

from . import _core

#: The blob table's row type: the columns of `neopipe run`'s CSV, in its order.
BLOB_DTYPE = _core.blob_dtype()


class Graph:
    """A neopipe graph (a YAML spec, as in examples/*.yaml), run one frame at a time.

    Make one with Graph.load(path), Graph.from_yaml(text) or Graph.blobs(...) (the built-in
    gray -> threshold -> blobs graph of `neopipe run`). A spec that does not validate raises
    neopipe.GraphError (a ValueError) with the CLI's "file:line:column: message".

    process(frame) runs the graph on one frame and returns the frame's blob table. The frame is
    read in place: a C-contiguous uint8 array (or one whose rows are padded, such as a crop
    frame[y0:y1, x0:x1]) is not copied, and the interpreter lock is released while the engine
    runs, so other Python threads go on. A frame in another colour layout than the graph's source
    (BGR for a gray8 graph, or gray for bgr8) is converted, which copies it.

    A graph keeps state from frame to frame, as a stream does: delay edges see the previous
    frame, the `frame` column counts up, and every frame must have the first one's size.
    reset() starts again.
    """

    def __init__(self, core):
        self._core = core

    @classmethod
    def load(cls, path):
        """Load a graph spec from a YAML file (FileNotFoundError if it is not there)."""
        return cls(_core.Graph.load(os.fspath(path)))

    @classmethod
    def from_yaml(cls, text, origin="<yaml text>"):
        """Make a graph from the text of a YAML spec; `origin` names it in error messages."""
        return cls(_core.Graph.from_yaml(text, origin))

    @classmethod
    def blobs(cls, threshold=None, connectivity=8, source="gray8"):
        """The built-in blob graph: gray -> threshold -> blobs, weighted by the gray values.

        threshold: None or "otsu" (Otsu's per frame), or T in 0..255 (foreground is value > T).
        connectivity: 4 or 8. source: "gray8" or "bgr8" (BT.601 gray first), the frames it takes
        without a conversion.
        """
        return cls(_core.Graph.blobs(threshold, connectivity, source))

    def process(self, frame):
        """Run one frame (numpy uint8, H x W or H x W x 3 BGR); return its blob table.

        Raises ValueError for a frame of another dtype, shape or layout (the message says which
        and why), of zero size, or of another size than the graph's first frame, and when the
        graph has no blob output (process_outputs then gives what it has).
        """
        return self._core.process(frame)

    def process_outputs(self, frame):
        """Run one frame; return every output of the graph by name.

        Images come back as new numpy arrays, histograms as 256 counts, blob lists as tables.
        """
        return self._core.process_outputs(frame)

    def reset(self):
        """Forget the frames seen: delays start from their initial values, frames from 0."""
        self._core.reset()

    @property
    def name(self):
        """The spec's name."""
        return self._core.name

    @property
    def origin(self):
        """Where the spec came from (its file, or a description)."""
        return self._core.origin

    @property
    def outputs(self):
        """The graph's output names, in declaration order."""
        return self._core.outputs

    @property
    def source_type(self):
        """What frames the graph's source takes: "gray8" or "bgr8"."""
        return self._core.source_type

    @property
    def frames(self):
        """Frames processed since the graph was made or reset."""
        return self._core.frames

    def __repr__(self):
        return f"neopipe.Graph({self.origin!r}, source {self.source_type}, outputs {self.outputs})"


def _is_path(source):
    return isinstance(source, (str, bytes, os.PathLike))


def run(source, graph=None, threshold=None, connectivity=8, threads=0, calib=None, height=0.0):
    """Run frames through a graph; yield each frame's blob table, in frame order.

    source: a video file, an image file or a directory of images (as `neopipe run` takes them;
        a list of such paths also works), or an iterable of numpy frames: uint8, gray H x W or
        BGR H x W x 3 as cv2 gives them, every one of the first one's size.
    graph: a neopipe.Graph or the path of a YAML spec; None is the built-in blob graph, gray ->
        threshold -> blobs (8-connected), which takes `threshold` (None or "otsu": Otsu's per
        frame; T in 0..255: value > T is foreground) and `connectivity` (4 or 8).
    threads: worker threads; 0 is one per hardware thread.
    calib: a calibration file (neopipe calibrate): the tables get X, Y, the weighted centroid on
        the workspace (mm), as `neopipe run --calib` adds them; `height`: the blobs' centres lie
        that far above the calibrated plane (mm; needs the full model). A calibration made for
        another image size raises RuntimeError at the first frame, as the CLI does.

    Yields numpy structured arrays of BLOB_DTYPE (frame, blob, area, cx, cy, x0, y0, w, h, wcx,
    wcy; with calib also X, Y), one per frame; the tables are `neopipe run`'s, number for number. Several frames are in
    flight at once, as in the CLI: numpy frames are read in place (not copied) until their table
    has been yielded, so do not write into a frame before then. Files are decoded on a thread of
    their own, a video gray from its luma plane as the CLI reads it.

    Errors are the CLI's one-line messages: FileNotFoundError for a path that is not there,
    ValueError for a bad frame (dtype, shape, layout, size) or option, neopipe.GraphError (a
    ValueError) for a graph that does not validate, RuntimeError for a file that cannot be read.
    The tables of the frames before an error are yielded first.
    """
    if graph is not None:
        if threshold is not None or connectivity != 8:
            raise ValueError("threshold and connectivity configure the built-in blob graph; "
                             "with a graph, set them in its spec")
        if _is_path(graph):
            graph = Graph.load(graph)
        if not isinstance(graph, Graph):
            raise TypeError(f"graph: a neopipe.Graph or a path, not {type(graph).__name__}")
    core_graph = graph._core if graph is not None else None
    if not isinstance(threads, int) or threads < 0:
        raise ValueError(f"threads {threads!r}: must be 0 (one per hardware thread) or more")
    calib = os.fsdecode(calib) if calib is not None else ""
    height = float(height)
    if _is_path(source):
        return _core.stream_files(core_graph, threshold, connectivity, threads, calib, height, [os.fsdecode(source)])
    if isinstance(source, (list, tuple)) and source and all(_is_path(s) for s in source):
        return _core.stream_files(core_graph, threshold, connectivity, threads, calib, height,
                                  [os.fsdecode(s) for s in source])
    return _core.stream_frames(core_graph, threshold, connectivity, threads, calib, height, source)
