"""Calibration, simulator, map-maker and navigator: the same results as the CLI's (JSON-equal dictionaries)."""

import json

import cv2
import numpy as np
import pytest

import neopipe
from conftest import cli_error

# Wall time: the only entries of `neopipe nav --trials --json` that differ from run to run.
TIMING = {"seconds", "frames_per_second"}


@pytest.fixture(scope="module")
def world(cli, tmp_path_factory):
    path = tmp_path_factory.mktemp("world") / "world.yaml"
    cli("sim", "world", "--objects", 100, "--seed", 1, "--out", path)
    return path


def test_sim_world_is_the_clis(cli, world):
    mine = neopipe.sim.world(objects=100, seed=1)
    theirs = neopipe.sim.load_world(world)
    np.testing.assert_array_equal(mine.objects, theirs.objects)
    assert mine.size == theirs.size == (500.0, 500.0) and mine.marble_diameter == theirs.marble_diameter
    assert len(mine) == 100


@pytest.mark.parametrize("camera, extra", [("global", []), ("onboard", ["--pose", "250,250,30"])])
def test_sim_render_is_the_clis(cli, world, tmp_path, camera, extra):
    png, truth = tmp_path / "frame.png", tmp_path / "truth.csv"
    cli("sim", "render", "--world", world, "--camera", camera, *extra, "--out", png, "--truth", truth)
    pose = (250, 250, 30) if extra else None
    image, rows = neopipe.sim.render(world, camera=camera, pose=pose)
    np.testing.assert_array_equal(image, cv2.imread(str(png), cv2.IMREAD_UNCHANGED))
    theirs = np.loadtxt(truth, delimiter=",", skiprows=1, ndmin=2)
    np.testing.assert_array_equal(rows["id"], theirs[:, 0])
    np.testing.assert_allclose(np.column_stack([rows["u"], rows["v"], rows["u0"], rows["v0"]]), theirs[:, 1:],
                               rtol=0, atol=1e-12)
    # The blobs of a rendered frame: through the engine at once.
    assert len(neopipe.Graph.blobs().process(image)) > 0


def test_map_is_the_clis_json(cli, world):
    theirs = json.loads(cli("map", "--world", world, "--json").stdout)
    assert neopipe.map.make(world) == theirs
    assert neopipe.map.make(neopipe.sim.load_world(world)) == theirs
    options = ["--window", 60, "--sigma", 0.5, "--descriptions", "paper", "--cost", "distance"]
    theirs = json.loads(cli("map", "--world", world, "--from", 0, "--to", 8, "--json", *options).stdout)
    mine = neopipe.map.route(world, 0, 8, cost="distance", window=60, sigma=0.5, descriptions="paper")
    assert mine == theirs and "custom_map_text" in mine
    assert neopipe.map.custom_map(world, 0, 8, cost="distance", window=60, sigma=0.5,
                                  descriptions="paper") == theirs["custom_map_text"]


def test_an_unreachable_goal_is_in_the_dict_as_in_the_clis(cli, world):
    completed = cli("map", "--world", world, "--from", 3, "--to", 41, "--json", check=False)
    assert completed.returncode == 3
    mine = neopipe.map.route(world, 3, 41)
    assert mine == json.loads(completed.stdout) and mine["unreachable"] == cli_error(completed, "map")
    with pytest.raises(ValueError, match="cannot be reached"):
        neopipe.map.custom_map(world, 3, 41)


def test_map_errors_are_the_clis(cli, world, tmp_path):
    for args, kwargs in [(["--window", -5], {"window": -5}),
                         (["--window", 900], {"window": 900}),
                         (["--from", -1, "--to", 2], {"start": -1, "goal": 2}),
                         (["--sigma", -1], {"sigma": -1})]:
        message = cli_error(cli("map", "--world", world, *args, check=False), "map").split(" (see neopipe")[0]
        with pytest.raises(ValueError) as e:
            neopipe.map.make(world, **kwargs)
        assert str(e.value) == message
    missing = tmp_path / "nowhere.yaml"
    with pytest.raises(FileNotFoundError) as e:
        neopipe.map.make(missing)
    assert str(e.value) == cli_error(cli("map", "--world", missing, check=False), "map")


def test_nav_trials_are_the_clis_json(cli, world):
    args = ["--trials", 6, "--sigma-map", 1.0, "--seed", 4, "--threads", 2, "--json"]
    theirs = json.loads(cli("nav", "--world", world, *args).stdout)
    mine = neopipe.nav.trials(world, 6, sigma_map=1.0, seed=4, threads=2)
    assert set(mine) == set(theirs)
    assert {k: v for k, v in mine.items() if k not in TIMING} == {k: v for k, v in theirs.items() if k not in TIMING}
    assert mine["trials"] == 6 and len(mine["journeys"]) == 6
    with pytest.raises(ValueError) as e:
        neopipe.nav.trials(world, 0, sigma_map=1.0)
    assert str(e.value) == cli_error(cli("nav", "--world", world, "--trials", 0, check=False), "nav").split(" (see")[0]
    with pytest.raises(ValueError, match="--realism dreamy"):
        neopipe.nav.trials(world, 2, realism="dreamy")


CHESSBOARDS = [f"left{i:02d}.jpg" for i in (1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14)]


def test_calibrate_and_map_points_as_the_cli(cli, opencv_data, tmp_path):
    images = [opencv_data / name for name in CHESSBOARDS]
    out = tmp_path / "calib.yaml"
    cli("calibrate", "--target", "chessboard:9x6:25mm", *images, "--out", out, "-q")
    calibration = neopipe.calibrate(images, "chessboard:9x6:25mm", out=tmp_path / "mine.yaml")
    loaded = neopipe.Calibration.load(out)
    assert calibration.model == loaded.model == "full" and calibration.image_size == (640, 480)
    assert calibration.report["views_used"] == loaded.report["views_used"]
    np.testing.assert_allclose(calibration.homography, loaded.homography, rtol=1e-9, atol=0)
    np.testing.assert_allclose(calibration.camera_matrix, loaded.camera_matrix, rtol=1e-9)
    assert (tmp_path / "mine.yaml").exists()

    uv = np.array([[320.0, 240.0], [10.5, 20.25], [600, 400]])
    pairs = tmp_path / "uv.csv"
    pairs.write_text("u,v\n" + "".join(f"{u},{v}\n" for u, v in uv))
    mapped = cli("calibrate", "map", "--calib", out, pairs).stdout.splitlines()
    theirs = np.array([[float(x) for x in line.split(",")[2:]] for line in mapped[1:]])
    xy = loaded.image_to_world(uv)
    np.testing.assert_array_equal(xy, theirs)
    np.testing.assert_allclose(loaded.world_to_image(xy), uv, atol=1e-6)
    assert loaded.image_to_world(uv[0]).shape == (2,)
    above = loaded.image_to_world(uv, height=2.5)
    assert not np.allclose(above, xy)
    np.testing.assert_allclose(loaded.world_to_image(above, height=2.5), uv, atol=1e-6)


def test_calibration_errors_are_the_clis(cli, opencv_data, tmp_path):
    missing = tmp_path / "nowhere.yaml"
    with pytest.raises(FileNotFoundError) as e:
        neopipe.Calibration.load(missing)
    completed = cli("calibrate", "map", "--calib", missing, check=False)
    assert str(e.value) == cli_error(completed, "calibrate map")
    blank = tmp_path / "blank.png"
    cv2.imwrite(str(blank), np.zeros((480, 640), np.uint8))
    completed = cli("calibrate", "--target", "chessboard:9x6:25mm", blank, "--out", tmp_path / "c.yaml", "-q",
                    check=False)
    with pytest.raises(ValueError) as e:
        neopipe.calibrate([blank], "chessboard:9x6:25mm")
    assert str(e.value) == cli_error(completed, "calibrate")
    with pytest.raises(ValueError, match="--target chessboard:9: expected"):
        neopipe.calibrate([blank], "chessboard:9")
    loaded_ok = tmp_path / "c2.yaml"
    cli("calibrate", "--target", "chessboard:9x6:25mm", opencv_data / "left01.jpg", "--out", loaded_ok, "-q")
    c = neopipe.Calibration.load(loaded_ok)
    for bad in (np.zeros((3, 3)), np.zeros(5), np.zeros((2, 2, 2))):
        with pytest.raises(ValueError, match="expected N x 2"):
            c.image_to_world(bad)
    with pytest.raises(ValueError, match="homography"):
        c.image_to_world(np.zeros((1, 2)), height=2.5)  # the plane homography has no camera to lift points with


def test_calibrate_from_point_pairs_as_the_cli(cli, tmp_path):
    pairs = tmp_path / "pairs.csv"
    rows = [(u, v, 0.25 * u - 3, 0.25 * v + 7) for u in (0, 150, 400, 630) for v in (5, 240, 470)]
    pairs.write_text("u,v,X,Y\n" + "".join(f"{u},{v},{x},{y}\n" for u, v, x, y in rows))
    cli("calibrate", "--points", pairs, "--image-size", "640x480", "--out", tmp_path / "c.yaml")
    theirs = neopipe.Calibration.load(tmp_path / "c.yaml")
    mine = neopipe.calibrate(points=pairs, image_size=(640, 480))
    assert mine.model == theirs.model == "homography" and mine.image_size == (640, 480)
    np.testing.assert_allclose(mine.homography, theirs.homography, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(mine.image_to_world(np.array([[100.0, 100.0]])), [[22.0, 32.0]], atol=1e-9)
    with pytest.raises(ValueError, match="only the homography"):
        neopipe.calibrate(points=pairs, model="full")
    with pytest.raises(ValueError, match="either target with images, or points"):
        neopipe.calibrate()


def test_a_missing_target_image_is_file_not_found_as_the_cli_says(cli, tmp_path):
    missing = tmp_path / "nowhere.png"
    completed = cli("calibrate", "--target", "chessboard:9x6:25mm", missing, "--out", tmp_path / "c.yaml", "-q",
                    check=False)
    with pytest.raises(FileNotFoundError) as e:
        neopipe.calibrate([missing], "chessboard:9x6:25mm")
    assert str(e.value) == cli_error(completed, "calibrate")
    with pytest.raises(FileNotFoundError) as e:
        neopipe.sim.load_world(tmp_path / "nowhere.yaml")
    assert str(e.value).endswith("nowhere.yaml: no such file")
