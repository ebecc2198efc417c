"""Calibrations of the global camera: neopipe.Calibration and neopipe.calibrate."""

import os

from . import _core


class Calibration:
    """A camera calibration: pixels <-> workspace (mm), as `neopipe calibrate` writes it.

    Calibration.load(path) reads the OpenCV FileStorage YAML file; neopipe.calibrate(...) makes
    one. image_to_world(uv) and world_to_image(xy) map numpy arrays of points (N x 2, or one
    point of shape (2,)); `height` (mm) puts the points that far above the calibrated plane (a
    marble's centre), which needs the full model. Also: model ("homography" or "full"),
    image_size, homography (3 x 3, on undistorted pixels for the full model), camera_matrix,
    distortion_coefficients and report (the error report, mm and px).
    """

    def __init__(self, core):
        self._core = core

    @classmethod
    def load(cls, path):
        """Read a calibration file (FileNotFoundError if it is not there, ValueError if malformed)."""
        return cls(_core.Calibration.load(os.fspath(path)))

    def save(self, path):
        """Write the calibration as OpenCV FileStorage YAML (what `neopipe run --calib` reads)."""
        self._core.save(os.fspath(path))

    def image_to_world(self, uv, height=0.0):
        """Workspace X, Y (mm) of pixels `uv` (N x 2 array of u, v), `height` mm above the plane."""
        return self._core.image_to_world(uv, height)

    def world_to_image(self, xy, height=0.0):
        """Pixels u, v where workspace points `xy` (N x 2, mm), `height` mm up, appear."""
        return self._core.world_to_image(xy, height)

    model = property(lambda self: self._core.model, doc='"homography" or "full".')
    image_size = property(lambda self: self._core.image_size, doc="(width, height) px, or None if unknown.")
    homography = property(lambda self: self._core.homography, doc="The 3 x 3 image-to-world matrix.")
    camera_matrix = property(lambda self: self._core.camera_matrix, doc="3 x 3 intrinsics (full model).")
    distortion_coefficients = property(lambda self: self._core.distortion_coefficients,
                                       doc="OpenCV's k1, k2, p1, p2, k3 (full model).")
    report = property(lambda self: self._core.report,
                      doc="The error report: fit and held-out errors (mm), reprojection RMS (px), views and points.")

    def __repr__(self):
        return f"neopipe.Calibration(model {self.model!r}, image size {self.image_size})"


def calibrate(images=(), target=None, *, points=None, target_origin=(0.0, 0.0, 0.0), model="auto",
              inlier_mm=2.0, image_size=None, out=None):
    """Calibrate the global camera, as `neopipe calibrate` does; return a Calibration.

    From images of a target: `target` is "dots:COLSxROWS:PITCHmm" or "chessboard:COLSxROWS:SQUAREmm";
    the first image shows the target lying on the workspace with its first point at
    `target_origin` (X, Y mm, and optionally its rows' direction from East, degrees); the others,
    anywhere, help fit the lens. model: "homography" (the paper's A), "full" (lens + plane) or
    "auto" (full from 3 views found).
    From point pairs: `points` is a CSV file u,v,X,Y (pixel, workspace mm); only the homography
    fits them; `image_size` (width, height) records where they came from.
    inlier_mm: RANSAC's outlier distance. out: also write the calibration file there.
    Errors are the CLI's messages: FileNotFoundError for a missing image, ValueError for a target
    not found in the first image, views of different sizes, or bad options.
    """
    if isinstance(images, (str, os.PathLike)):
        images = [images]
    core = _core.calibrate([os.fspath(i) for i in images], target or "",
                           os.fspath(points) if points is not None else None,
                           [float(v) for v in target_origin], model, float(inlier_mm),
                           tuple(image_size) if image_size is not None else None)
    calibration = Calibration(core)
    if out is not None:
        calibration.save(out)
    return calibration
