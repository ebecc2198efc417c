#!/usr/bin/env python3
# %% [markdown]
# # Blobs of a video, from Python
#
# A notebook-style walk through neopipe's Python module (each `# %%` is a cell: VS Code, Spyder,
# or Jupyter with jupytext run them one by one; `python3 examples/python/blob_counts.py` runs them
# all). A video goes in, the blob table comes out as a pandas DataFrame, and a plot of the blob
# count per frame is saved as a PNG.
#
#     PYTHONPATH=build/python python3 examples/python/blob_counts.py [VIDEO] [--out DIR]
#
# (no PYTHONPATH once the module is installed: scripts/install_python.sh). Without VIDEO it takes
# the demo video `./scripts/demo.sh` makes (build/demo/marbles.mp4) if it is there, else OpenCV's
# sample vtest.avi (Debian: opencv-doc).

# %%
import argparse
import pathlib
import sys
import time

import numpy as np
import pandas as pd

import neopipe

ROOT = pathlib.Path(__file__).resolve().parents[2]
CANDIDATES = [ROOT / "build" / "demo" / "marbles.mp4", pathlib.Path("/usr/share/doc/opencv-doc/examples/data/vtest.avi")]

parser = argparse.ArgumentParser(description="Blob counts per frame of a video, with neopipe from Python")
parser.add_argument("video", nargs="?", help="a video file (default: the demo video, else OpenCV's vtest.avi)")
parser.add_argument("--out", default=".", help="directory for blob_counts.png and blobs.csv")
args = parser.parse_args([a for a in sys.argv[1:] if not a.startswith("-f=")])  # Jupyter passes -f=...
video = pathlib.Path(args.video) if args.video else next((c for c in CANDIDATES if c.exists()), None)
if video is None:
    sys.exit("no video: give one, run ./scripts/demo.sh, or install opencv-doc")
out = pathlib.Path(args.out)
out.mkdir(parents=True, exist_ok=True)
print(f"video: {video}")

# %% [markdown]
# ## The built-in blob graph over every frame
#
# `neopipe.run` decodes the video on a thread of its own and keeps several frames in flight; it
# yields one numpy structured array per frame with the CLI's columns (frame, blob, area, cx, cy,
# x0, y0, w, h, wcx, wcy). Frames without blobs yield empty tables, so the count per frame is the
# length of each table.

# %%
t0 = time.perf_counter()
tables = list(neopipe.run(video))  # Otsu's threshold per frame, 8-connected
seconds = time.perf_counter() - t0
counts = np.array([len(t) for t in tables])
print(f"{len(tables)} frames, {counts.sum()} blobs in {seconds:.2f} s ({len(tables) / seconds:.0f} frames/s)")

# %% [markdown]
# ## As a DataFrame

# %%
blobs = neopipe.to_pandas(tables)
print(blobs.head())
per_frame = blobs.groupby("frame").agg(blobs=("blob", "size"), mean_area=("area", "mean"))
print(per_frame.describe())
blobs.to_csv(out / "blobs.csv", index=False)  # the rows `neopipe run VIDEO --out blobs.csv` writes

# %% [markdown]
# ## Blobs per frame, as a picture

# %%
import matplotlib

matplotlib.use("Agg")  # files only: no display needed
import matplotlib.pyplot as plt

fig, ax = plt.subplots(figsize=(8, 3.5))
ax.plot(np.arange(len(counts)), counts, lw=1)
ax.set_xlabel("frame")
ax.set_ylabel("blobs")
ax.set_title(f"{video.name}: blobs per frame (neopipe, Otsu threshold)")
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(out / "blob_counts.png", dpi=100)
print(f"plot: {out / 'blob_counts.png'}")

# %% [markdown]
# ## Frames you already have: numpy arrays from cv2
#
# Frames from `cv2.VideoCapture` (BGR) go in as they are and are read in place; here with a fixed
# threshold and one graph of our own, one frame at a time.

# %%
try:
    import cv2
except ImportError:
    cv2 = None
if cv2 is not None:
    capture = cv2.VideoCapture(str(video))
    graph = neopipe.Graph.blobs(threshold=100, source="bgr8")
    sizes = []
    for _ in range(50):
        ok, frame = capture.read()
        if not ok:
            break
        table = graph.process(frame)
        sizes.append(pd.Series(table["area"]).median() if len(table) else 0)
    print(f"first {len(sizes)} frames, threshold 100: median blob area per frame {np.median(sizes):.1f} px")
