"""Bad input: Python exceptions with the CLI's one-line messages, never a crash."""

import numpy as np
import pytest

import neopipe
from conftest import cli_error

GOOD = np.zeros((48, 64), np.uint8)


@pytest.mark.parametrize(
    "frame, words",
    [
        (np.zeros((48, 64), np.float32), "dtype float32"),
        (np.zeros((48, 64), np.int16), "dtype int16"),
        (np.zeros((48, 64), bool), "dtype bool"),
        (np.zeros((48, 64, 4), np.uint8), "shape (48, 64, 4)"),
        (np.zeros(64, np.uint8), "shape (64,)"),
        (np.zeros((2, 48, 64, 3), np.uint8), "shape (2, 48, 64, 3)"),
        (np.zeros((0, 64), np.uint8), "shape (0, 64) is empty"),
        (np.zeros((48, 0, 3), np.uint8), "shape (48, 0, 3) is empty"),
        (np.zeros((48, 64), np.uint8)[:, ::2], "strides (64, 2)"),
        (np.zeros((48, 64), np.uint8).T, "strides (1, 64)"),
        (np.zeros((48, 64), np.uint8)[::-1], "strides (-64, 1)"),
        (np.zeros((48, 64, 3), np.uint8)[:, :, ::-1], "strides (192, 3, -1)"),
    ],
)
def test_bad_frames_are_value_errors(frame, words):
    graph = neopipe.Graph.blobs(threshold=10)
    with pytest.raises(ValueError, match=r"^frame: ") as e:
        graph.process(frame)
    assert words in str(e.value)
    with pytest.raises(ValueError, match=r"^frame 0: ") as e:
        next(iter(neopipe.run([frame])))
    assert words in str(e.value)
    # The graph is still good for good frames.
    assert len(graph.process(GOOD)) == 0


def test_frames_of_another_size_or_kind():
    graph = neopipe.Graph.blobs(threshold=10)
    graph.process(GOOD)
    with pytest.raises(ValueError, match="frame 1 is 32x48 but the first was 64x48"):
        graph.process(np.zeros((48, 32), np.uint8))
    stream = neopipe.run([GOOD, GOOD, np.zeros((48, 32), np.uint8)], threshold=10, threads=1)
    assert len(list(zip(range(2), stream))) == 2  # the tables before the error come first
    with pytest.raises(ValueError, match="48"):
        next(stream)
    with pytest.raises(ValueError, match="frame 1: a str, not a numpy array"):
        list(neopipe.run([GOOD, "not a frame"]))
    with pytest.raises(TypeError):
        neopipe.run(42)


def test_bad_options():
    with pytest.raises(ValueError, match="threshold 300: must be 0..255"):
        neopipe.run([GOOD], threshold=300)
    with pytest.raises(ValueError, match="threshold 'mean'"):
        neopipe.Graph.blobs(threshold="mean")
    with pytest.raises(ValueError, match="connectivity 6: must be 4 or 8"):
        neopipe.run([GOOD], connectivity=6)
    with pytest.raises(ValueError, match="threads"):
        neopipe.run([GOOD], threads=-1)
    with pytest.raises(ValueError, match="with a graph, set them in its spec"):
        neopipe.run([GOOD], graph=neopipe.Graph.blobs(), threshold=3)


def test_missing_files_say_so_as_the_cli_does(cli, tmp_path):
    missing = tmp_path / "nowhere.mp4"
    with pytest.raises(FileNotFoundError) as e:
        next(iter(neopipe.run(missing)))
    assert str(e.value) == cli_error(cli("run", missing, check=False), "run")
    with pytest.raises(FileNotFoundError, match="cannot open the graph spec"):
        neopipe.Graph.load(tmp_path / "nowhere.yaml")
    with pytest.raises(FileNotFoundError):
        neopipe.read_table(tmp_path / "nowhere.csv")


def test_unreadable_video_is_a_runtime_error_with_the_clis_message(cli, tmp_path):
    video = tmp_path / "closed.mp4"
    video.write_bytes(b"\x00\x00\x00\x18ftypmp42" + bytes(200))  # a header, then nothing
    with pytest.raises(RuntimeError) as e:
        list(neopipe.run(video))
    assert str(e.value) == cli_error(cli("run", video, check=False), "run")


GRAPHS = {
    "unknown kernel": "nodes:\n  - {name: src, kernel: source}\n  - {name: b, kernel: blobz, inputs: {in: src}}\noutputs: [b]\n",
    "bad parameter": "nodes:\n  - {name: src, kernel: source}\n  - {name: b, kernel: blobs, params: {connectivity: 6}, inputs: {in: src}}\noutputs: [b]\n",
    "cycle without delay": (
        "nodes:\n  - {name: src, kernel: source, params: {format: gray}}\n"
        "  - {name: a, kernel: add, inputs: {a: src, b: c}}\n"
        "  - {name: c, kernel: add, inputs: {a: a, b: src}}\n"
        "  - {name: b, kernel: blobs, inputs: {in: c}}\noutputs: [b]\n"),
    "not yaml": "nodes: [\n",
}


@pytest.mark.parametrize("what", sorted(GRAPHS))
def test_graphs_that_do_not_validate(cli, tmp_path, what):
    path = tmp_path / "bad.yaml"
    path.write_text(GRAPHS[what])
    frame = tmp_path / "frame.png"
    import cv2
    cv2.imwrite(str(frame), GOOD)
    expected = cli_error(cli("run", frame, "--graph", path, check=False), "run")
    with pytest.raises(neopipe.GraphError) as e:
        neopipe.Graph.load(path)
    assert str(e.value) == expected
    assert isinstance(e.value, ValueError)
    with pytest.raises(neopipe.GraphError) as e:
        next(iter(neopipe.run(frame, graph=str(path))))
    assert str(e.value) == expected


def test_a_graph_without_blobs(cli, tmp_path, examples):
    edges = neopipe.Graph.load(examples / "edges.yaml")
    frame = np.zeros((48, 64, 3) if edges.source_type == "bgr8" else (48, 64), np.uint8)
    if "blobs" not in [str(o) for o in edges.outputs]:
        with pytest.raises(ValueError, match="no output of type blobs"):
            edges.process(frame)
        assert set(edges.process_outputs(frame)) == set(edges.outputs)
        with pytest.raises(neopipe.GraphError, match="no output of type blobs"):
            neopipe.run([frame], graph=edges)
