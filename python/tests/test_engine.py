"""Graph.process and neopipe.run against OpenCV and against the CLI's tables."""

import shutil
import threading
import tracemalloc

import cv2
import numpy as np
import pytest

import neopipe
from conftest import cli_error

IMAGES = ["detect_blob.png", "pic1.png", "fruits.jpg", "baboon.jpg", "left01.jpg", "chessboard.png"]
COLUMNS = ("frame", "blob", "area", "cx", "cy", "x0", "y0", "w", "h", "wcx", "wcy")


def opencv_blobs(gray, threshold, connectivity):
    """OpenCV's stats and centroids of the components of gray > threshold, in raster order of their first pixel.

    (OpenCV's default 8-connected algorithm works in 2 x 2 blocks and may number components out of that
    order; neopipe's table is in it, as tests/kernels/kernel_test_support.hpp renumbers too.)
    """
    n, labels, stats, centroids = cv2.connectedComponentsWithStats((gray > threshold).astype(np.uint8),
                                                                   connectivity=connectivity)
    found, first = np.unique(labels.ravel(), return_index=True)
    order = found[np.argsort(first)]
    order = order[order != 0]
    return stats[order], centroids[order], n - 1


def assert_same_as_opencv(table, gray, threshold, connectivity):
    stats, centroids, n = opencv_blobs(gray, threshold, connectivity)
    assert len(table) == n
    np.testing.assert_array_equal(table["area"], stats[:, cv2.CC_STAT_AREA])
    np.testing.assert_array_equal(table["x0"], stats[:, cv2.CC_STAT_LEFT])
    np.testing.assert_array_equal(table["y0"], stats[:, cv2.CC_STAT_TOP])
    np.testing.assert_array_equal(table["w"], stats[:, cv2.CC_STAT_WIDTH])
    np.testing.assert_array_equal(table["h"], stats[:, cv2.CC_STAT_HEIGHT])
    np.testing.assert_allclose(table["cx"], centroids[:, 0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(table["cy"], centroids[:, 1], rtol=0, atol=1e-9)
    np.testing.assert_array_equal(table["blob"], np.arange(n))


def test_table_columns_are_the_clis():
    assert neopipe.BLOB_DTYPE.names == COLUMNS


@pytest.mark.parametrize("name", IMAGES)
@pytest.mark.parametrize("connectivity", [4, 8])
def test_blobs_match_opencv_on_real_images(opencv_data, name, connectivity):
    gray = cv2.imread(str(opencv_data / name), cv2.IMREAD_GRAYSCALE)
    for threshold in (60, 128, 200):
        graph = neopipe.Graph.blobs(threshold=threshold, connectivity=connectivity)
        assert_same_as_opencv(graph.process(gray), gray, threshold, connectivity)


@pytest.mark.parametrize("name", IMAGES)
def test_otsu_and_colour_frames_match_opencv(opencv_data, name):
    bgr = cv2.imread(str(opencv_data / name), cv2.IMREAD_COLOR)
    gray = cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY)
    otsu, _ = cv2.threshold(gray, 0, 255, cv2.THRESH_BINARY | cv2.THRESH_OTSU)
    # A bgr8 graph converts in the graph; a gray8 graph given colour converts it on the way in.
    for graph in (neopipe.Graph.blobs(source="bgr8"), neopipe.Graph.blobs()):
        table = graph.process(bgr)
        assert_same_as_opencv(table, gray, int(otsu), 8)
    # Weighted centroids: by the gray values.
    table = neopipe.Graph.blobs(threshold=128).process(gray)
    ys, xs = np.nonzero(gray > 128)
    if len(table):
        _, labels = cv2.connectedComponents((gray > 128).astype(np.uint8), connectivity=8)
        first = labels == 1
        w = gray[first].astype(np.float64)
        if w.sum() > 0:
            assert table["wcx"][0] == pytest.approx((np.nonzero(first)[1] * w).sum() / w.sum(), abs=1e-9)


def test_graph_load_and_from_yaml(examples, opencv_data):
    gray = cv2.imread(str(opencv_data / "pic1.png"), cv2.IMREAD_GRAYSCALE)
    bgr = cv2.cvtColor(gray, cv2.COLOR_GRAY2BGR)
    from_file = neopipe.Graph.load(examples / "blobs.yaml")
    from_text = neopipe.Graph.from_yaml((examples / "blobs.yaml").read_text())
    assert from_file.source_type == "bgr8" and from_file.outputs == ["blobs"]
    a, b = from_file.process(bgr), from_text.process(bgr)
    np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(a, neopipe.Graph.blobs().process(gray))
    outputs = from_file.process_outputs(bgr)
    assert list(outputs) == ["blobs"] and outputs["blobs"]["frame"].tolist() == [1] * len(a)
    assert from_file.frames == 2
    from_file.reset()
    assert from_file.frames == 0 and from_file.process(bgr)["frame"].tolist() == [0] * len(a)


def video_frames(path, limit=None):
    cap = cv2.VideoCapture(str(path))
    assert cap.isOpened()
    n = 0
    while limit is None or n < limit:
        ok, frame = cap.read()
        if not ok:
            break
        yield frame
        n += 1
    cap.release()


def test_run_on_cv2_videocapture_frames(opencv_data):
    frames = list(video_frames(opencv_data / "vtest.avi", 60))
    assert len(frames) == 60 and frames[0].shape == (576, 768, 3)
    tables = list(neopipe.run(iter(frames), threshold=100, connectivity=8, threads=2))
    assert [int(t["frame"][0]) for t in tables if len(t)] == [i for i, t in enumerate(tables) if len(t)]
    graph = neopipe.Graph.blobs(threshold=100, source="bgr8")
    for i, (frame, table) in enumerate(zip(frames, tables)):
        np.testing.assert_array_equal(table, graph.process(frame))
        if i % 20 == 0:
            assert_same_as_opencv(table, cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY), 100, 8)
    # A generator straight from cv2, gray frames, and every thread count: the same tables.
    gray = [cv2.cvtColor(f, cv2.COLOR_BGR2GRAY) for f in frames[:20]]
    one = list(neopipe.run(gray, threshold=100, threads=1))
    for threads in (0, 2):
        for a, b in zip(one, neopipe.run((g for g in gray), threshold=100, threads=threads)):
            np.testing.assert_array_equal(a, b)
    for a, b in zip(one, tables):
        np.testing.assert_array_equal(a, b)


def test_run_on_a_video_file_equals_the_cli(cli, opencv_data, tmp_path):
    video = opencv_data / "vtest.avi"
    out = tmp_path / "blobs.csv"
    cli("run", video, "--threshold", 100, "--out", out, "-q")
    table = neopipe.read_table(out)
    mine = neopipe.concat(neopipe.run(video, threshold=100))
    assert table.dtype == mine.dtype and len(table) > 1000
    np.testing.assert_array_equal(mine, table)
    cli("run", video, "--out", tmp_path / "otsu.jsonl", "-q")
    np.testing.assert_array_equal(neopipe.concat(neopipe.run(str(video))), neopipe.read_table(tmp_path / "otsu.jsonl"))


def test_run_on_images_and_a_directory_equals_the_cli(cli, opencv_data, tmp_path, examples):
    for i in range(1, 7):
        shutil.copy(opencv_data / f"left0{i}.jpg", tmp_path / f"left0{i}.jpg")
    cli("run", tmp_path, "--graph", examples / "blobs.yaml", "--out", tmp_path / "dir.csv", "-q")
    mine = neopipe.concat(neopipe.run(tmp_path, graph=examples / "blobs.yaml"))
    np.testing.assert_array_equal(mine, neopipe.read_table(tmp_path / "dir.csv"))
    one = neopipe.concat(neopipe.run(str(tmp_path / "left01.jpg"), threshold=128, connectivity=4))
    cli("run", tmp_path / "left01.jpg", "--threshold", 128, "--connectivity", 4, "--out", tmp_path / "one.csv", "-q")
    np.testing.assert_array_equal(one, neopipe.read_table(tmp_path / "one.csv"))


def test_to_pandas(opencv_data):
    pd = pytest.importorskip("pandas")
    tables = list(neopipe.run(video_frames(opencv_data / "vtest.avi", 10), threshold=100))
    df = neopipe.to_pandas(tables)
    assert list(df.columns) == list(COLUMNS) and len(df) == sum(len(t) for t in tables)
    assert df["frame"].dtype == np.int64 and df["cx"].dtype == np.float64
    assert isinstance(neopipe.to_pandas(tables[0]), pd.DataFrame)


def test_frames_are_read_in_place():
    """A 1080p frame is not copied: the engine reads the caller's memory, and numpy allocates nothing frame-sized."""
    rng = np.random.default_rng(1)
    bgr = rng.integers(0, 150, (1080, 1920, 3), dtype=np.uint8)  # noise below the threshold ...
    for y, x in rng.integers(0, 1000, (200, 2)):
        bgr[y:y + 20, x:x + 30] = 250                               # ... and 200 bright patches
    gray = np.ascontiguousarray(bgr[:, :, 1])
    for frame, graph in ((bgr, neopipe.Graph.blobs(threshold=200, source="bgr8")),
                         (gray, neopipe.Graph.blobs(threshold=200))):
        graph.process(frame)  # the graph's own buffers are made on its first frame
        tracemalloc.start()
        table = graph.process(frame)
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        assert graph._core._last_frame_address == frame.ctypes.data
        assert peak < frame.nbytes / 20, f"{peak} bytes allocated for a {frame.nbytes}-byte frame"
        assert len(table) > 0
    # A crop (padded rows) is read in place too, with the contiguous copy's results.
    crop = gray[100:900, 200:1700]
    graph = neopipe.Graph.blobs(threshold=200)
    table = graph.process(crop)
    assert graph._core._last_frame_address == crop.ctypes.data
    np.testing.assert_array_equal(table, neopipe.Graph.blobs(threshold=200).process(crop.copy()))


def test_the_engine_runs_without_the_gil():
    """Two Python threads processing at once get the one-thread results (and no crash)."""
    rng = np.random.default_rng(2)
    frames = [rng.integers(0, 256, (480, 640), dtype=np.uint8) for _ in range(8)]
    expected = [neopipe.Graph.blobs(threshold=180).process(f) for f in frames]
    shared = neopipe.Graph.blobs(threshold=180)
    out = {}

    def work(name):
        g = neopipe.Graph.blobs(threshold=180)
        out[name] = [g.process(f) for f in frames]
        for f in frames:
            shared.process(f)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for name in out:
        for a, b in zip(out[name], expected):
            np.testing.assert_array_equal(a["area"], b["area"])
    assert shared.frames == 24


def calibration_from_points(cli, folder, size):
    """A plane homography from exact pairs (pixel -> mm: 0.5 mm per pixel, shifted), made for `size` images."""
    pairs = folder / "pairs.csv"
    rows = [(u, v, 0.5 * u + 10, 0.5 * v - 20) for u in (0, 100, 300, 600) for v in (0, 200, 450)]
    pairs.write_text("u,v,X,Y\n" + "".join(f"{u},{v},{x},{y}\n" for u, v, x, y in rows))
    out = folder / f"calib_{size}.yaml"
    cli("calibrate", "--points", pairs, "--image-size", size, "--out", out)
    return out


def test_run_with_a_calibration_adds_x_y_as_the_cli(cli, opencv_data, tmp_path):
    image = opencv_data / "left01.jpg"
    calib = calibration_from_points(cli, tmp_path, "640x480")
    cli("run", image, "--calib", calib, "--out", tmp_path / "xy.csv", "-q")
    theirs = neopipe.read_table(tmp_path / "xy.csv")
    mine = neopipe.concat(neopipe.run(image, calib=calib))
    assert mine.dtype.names == COLUMNS + ("X", "Y") and len(mine) > 10
    np.testing.assert_array_equal(mine, theirs)
    np.testing.assert_allclose(mine["X"], 0.5 * mine["wcx"] + 10, atol=1e-6)
    frames = [cv2.imread(str(image), cv2.IMREAD_GRAYSCALE)] * 2
    tables = list(neopipe.run(frames, calib=calib))
    np.testing.assert_array_equal(tables[0], theirs)


def test_a_calibration_of_another_camera(cli, opencv_data, tmp_path):
    image = opencv_data / "left01.jpg"
    calib = calibration_from_points(cli, tmp_path, "320x240")
    expected = cli_error(cli("run", image, "--calib", calib, check=False), "run")
    assert "made for 320x240 images" in expected
    with pytest.raises(RuntimeError) as e:
        list(neopipe.run(image, calib=calib))
    assert str(e.value) == expected
    with pytest.raises(RuntimeError, match="made for 320x240 images, but frame 0 of frames from Python is 640x480"):
        list(neopipe.run([cv2.imread(str(image), cv2.IMREAD_GRAYSCALE)], calib=calib))
    # The plane homography cannot lift points above the plane; the CLI refuses --height with it too.
    calib = calibration_from_points(cli, tmp_path, "640x480")
    expected = cli_error(cli("run", image, "--calib", calib, "--height", 2.5, check=False), "run")
    with pytest.raises(ValueError) as e:
        list(neopipe.run(image, calib=calib, height=2.5))
    assert str(e.value) == expected
    with pytest.raises(FileNotFoundError):
        neopipe.run(image, calib=tmp_path / "nowhere.yaml")


def test_process_releases_the_interpreter_lock():
    """While one thread is inside graph.process, another runs Python: it never waits the whole call out."""
    import sys
    import time
    rng = np.random.default_rng(3)
    frame = rng.integers(0, 256, (3000, 4000), dtype=np.uint8)
    graph = neopipe.Graph.blobs(threshold=128, connectivity=4)  # noise: a great many blobs, a long call
    graph.process(frame)
    call = {}

    def work():
        call["start"] = time.perf_counter()
        graph.process(frame)
        call["end"] = time.perf_counter()

    old = sys.getswitchinterval()
    sys.setswitchinterval(1e-4)
    try:
        stamps = []
        t = threading.Thread(target=work)
        t.start()
        while t.is_alive():
            stamps.append(time.perf_counter())
        t.join()
    finally:
        sys.setswitchinterval(old)
    inside = np.array([s for s in stamps if call["start"] <= s <= call["end"]])
    duration = call["end"] - call["start"]
    assert duration > 0.02 and len(inside) > 10
    gaps = np.diff(np.concatenate([[call["start"]], inside, [call["end"]]]))
    assert gaps.max() < duration / 2, f"the main thread stood still {gaps.max():.3f} s of a {duration:.3f} s call"
