#!/usr/bin/env python3
"""Soak test of `neopipe run --realtime` (issue 18): a long 1080p stream, a sink slower than the pace.

    scripts/soak.py [--minutes 30] [--sink-kbps 200] [--out build/soak]

Makes the stream once (cached in OUT): a 60 s clip of a simulated 1920x1080 global camera over 150
moving marbles (`neopipe sim video`, rig realism), repeated by FFmpeg without re-encoding to the
length asked for. Then runs `neopipe run --realtime` on it with the table on a pipe that this script
reads at SINK-KBPS kilobytes a second, slower than the table comes (about 150 rows of 60-80 bytes a
frame, 30 frames a second: some 350 kB/s), so the pipeline backs up and frames are dropped.

Every minute it records neopipe's resident and peak memory (/proc/PID/status) in OUT/memory.csv.
At the end it checks what the issue asks, and exits non-zero if any fails:
  - memory is flat: the last sample's resident size within 10% (and 16 MiB) of the sample at
    minute 2 (after start-up), and the peak never far above it;
  - drops were counted (the summary line says how many) and there were some;
  - every processed frame's rows were written: the table has a row for every frame the summary
    counts (a frame of this stream always has blobs), each row is whole (11 fields, numbers), and
    processed + dropped = the frames of the stream.
Writes OUT/soak.json with the figures (docs/reliability.md quotes them).
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CLIP_SECONDS = 60
FPS = 30


def fail(message: str) -> None:
    print(f"soak: {message}", file=sys.stderr)
    sys.exit(1)


def make_stream(neopipe: Path, out: Path, minutes: int) -> Path:
    stream = out / f"marbles_1080p_{minutes}min.mp4"
    if stream.exists():
        return stream
    world = out / "world150.yaml"
    clip = out / "marbles_1080p_60s.mp4"
    if not clip.exists():
        subprocess.run([neopipe, "sim", "world", "--objects", "150", "--seed", "5", "--out", world], check=True)
        print(f"soak: rendering the {CLIP_SECONDS} s clip (a few minutes)", file=sys.stderr)
        subprocess.run([neopipe, "sim", "video", "--world", world, "--resolution", "1920x1080",
                        "--frames", str(CLIP_SECONDS * FPS), "--fps", str(FPS), "--out", clip], check=True)
    loops = minutes * 60 // CLIP_SECONDS
    subprocess.run(["ffmpeg", "-nostdin", "-loglevel", "error", "-y", "-stream_loop", str(loops - 1), "-i", clip,
                    "-c", "copy", stream], check=True)
    return stream


def memory_kib(pid: int) -> tuple[int, int] | None:
    """(VmRSS, VmHWM) in KiB, or None once the process is gone."""
    try:
        text = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return None
    fields = dict(re.findall(r"^(VmRSS|VmHWM):\s+(\d+) kB", text, re.M))
    if "VmRSS" not in fields:
        return None
    return int(fields["VmRSS"]), int(fields["VmHWM"])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--minutes", type=int, default=30, help="length of the stream (whole minutes, default 30)")
    parser.add_argument("--sink-kbps", type=float, default=200.0,
                        help="how fast the sink reads the table, kB/s (default 200: slower than the pace)")
    parser.add_argument("--out", type=Path, default=ROOT / "build" / "soak", help="folder for the stream and results")
    parser.add_argument("--neopipe", type=Path, default=ROOT / "build" / "apps" / "neopipe")
    args = parser.parse_args()
    if args.minutes < 1:
        fail("--minutes must be at least 1")
    if not args.neopipe.exists():
        fail(f"{args.neopipe}: not found (build first: scripts/build.sh)")
    args.out.mkdir(parents=True, exist_ok=True)
    stream = make_stream(args.neopipe, args.out, args.minutes)
    total_frames = args.minutes * 60 * FPS

    table_path = args.out / "table.csv"
    stderr_path = args.out / "neopipe.stderr"
    with open(stderr_path, "wb") as err:
        proc = subprocess.Popen([args.neopipe, "run", "--realtime", stream], stdout=subprocess.PIPE, stderr=err)
    assert proc.stdout is not None
    os.set_blocking(proc.stdout.fileno(), False)

    samples: list[dict] = []
    start = time.monotonic()
    next_sample = start
    read_bytes = 0
    chunk = 4096
    with open(table_path, "wb") as table:
        while True:
            now = time.monotonic()
            if now >= next_sample:
                mem = memory_kib(proc.pid)
                if mem is not None:
                    samples.append({"minute": round((now - start) / 60, 2), "rss_kib": mem[0], "peak_kib": mem[1],
                                    "table_bytes": read_bytes})
                    print(f"soak: minute {samples[-1]['minute']:5.2f}: rss {mem[0] / 1024:7.1f} MiB, "
                          f"peak {mem[1] / 1024:7.1f} MiB, table {read_bytes / 1e6:8.1f} MB", file=sys.stderr)
                next_sample += 60
            try:
                data = proc.stdout.read(chunk)
            except BlockingIOError:
                data = None
            if data == b"":
                break
            if data:
                table.write(data)
                read_bytes += len(data)
            # The sink's pace: the bytes read so far may not run ahead of SINK-KBPS.
            ahead = read_bytes / (args.sink_kbps * 1000) - (time.monotonic() - start)
            time.sleep(max(ahead, 0.002))
    code = proc.wait()
    elapsed = time.monotonic() - start

    with open(args.out / "memory.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=["minute", "rss_kib", "peak_kib", "table_bytes"])
        writer.writeheader()
        writer.writerows(samples)

    summary = stderr_path.read_text(errors="replace").replace("\r", "\n")
    match = re.search(r"(\d+) frames, (\d+) dropped, (\d+) blobs", summary)
    problems = []
    if code != 0:
        problems.append(f"neopipe exited {code}")
    if not match:
        fail(f"no summary line in {stderr_path}")
    processed, dropped, blobs = (int(g) for g in match.groups())

    frames_in_table: set[int] = set()
    rows = 0
    bad_rows = 0
    with open(table_path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        for row in reader:
            rows += 1
            try:
                if len(row) != len(header):
                    raise ValueError
                [float(x) for x in row]
                frames_in_table.add(int(row[0]))
            except ValueError:
                bad_rows += 1
    raw_tail = table_path.read_bytes()[-1:]

    if processed + dropped != total_frames:
        problems.append(f"processed {processed} + dropped {dropped} != {total_frames} frames in the stream")
    if dropped == 0:
        problems.append("no frame dropped: the sink was not slower than the pace")
    if len(frames_in_table) != processed:
        problems.append(f"the table has rows of {len(frames_in_table)} frames, the summary counts {processed}")
    if rows != blobs:
        problems.append(f"the table has {rows} rows, the summary counts {blobs} blobs")
    if bad_rows or raw_tail != b"\n":
        problems.append(f"{bad_rows} malformed rows; last byte {raw_tail!r}")
    settled = [s for s in samples if s["minute"] >= 2]
    if len(settled) >= 2:
        base, last = settled[0]["rss_kib"], settled[-1]["rss_kib"]
        growth = last - base
        if growth > max(0.10 * base, 16 * 1024):
            problems.append(f"memory grew from {base} KiB at minute 2 to {last} KiB")
    else:
        growth = None

    result = {
        "stream": str(stream), "minutes": args.minutes, "frames": total_frames, "processed": processed,
        "dropped": dropped, "blobs": blobs, "rows": rows, "frames_in_table": len(frames_in_table),
        "bad_rows": bad_rows, "sink_kbps": args.sink_kbps, "elapsed_s": round(elapsed, 1), "exit": code,
        "rss_kib_min2": settled[0]["rss_kib"] if settled else None,
        "rss_kib_last": samples[-1]["rss_kib"] if samples else None,
        "rss_growth_kib": growth, "peak_kib": max((s["peak_kib"] for s in samples), default=None),
        "summary": match.group(0), "problems": problems,
    }
    (args.out / "soak.json").write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps(result, indent=2))
    if problems:
        fail("; ".join(problems))
    print("soak: passed", file=sys.stderr)


if __name__ == "__main__":
    main()
