"""Blob tables as files: read what `neopipe run` wrote, hand tables to pandas."""

import json
import os

import numpy as np

from ._core import blob_dtype

_INT_COLUMNS = {"frame": np.int64, "blob": np.int64, "area": np.int64,
                "x0": np.int32, "y0": np.int32, "w": np.int32, "h": np.int32}


def _dtype(names):
    return np.dtype([(n, _INT_COLUMNS.get(n, np.float64)) for n in names])


def read_table(path):
    """Read a blob table `neopipe run` wrote: CSV (header line first) or JSON Lines.

    Returns one numpy structured array of every row, with the file's columns (frame, blob, area,
    cx, cy, x0, y0, w, h, wcx, wcy, and mu20, mu11, mu02 or X, Y where the CLI added them), of the
    same types neopipe.run yields. to_pandas(table) makes it a DataFrame.
    """
    path = os.fspath(path)
    if not os.path.exists(path):
        raise FileNotFoundError(f"{path}: no such file")
    with open(path, encoding="utf-8") as f:
        first = f.readline()
        if first.lstrip().startswith("{"):
            rows = [json.loads(line) for line in [first, *f] if line.strip()]
            names = list(rows[0].keys())
            return np.array([tuple(r[n] for n in names) for r in rows], dtype=_dtype(names))
        names = first.strip().split(",")
        if not names or names[:2] != ["frame", "blob"]:
            raise ValueError(f"{path}: not a blob table (its header is {first.strip()!r})")
        text = f.read()
    dtype = _dtype(names)
    if not text.strip():
        return np.empty(0, dtype=dtype)
    from io import StringIO
    return np.loadtxt(StringIO(text), delimiter=",", dtype=dtype, ndmin=1)


def concat(tables):
    """One table of many (a list of tables, or what neopipe.run yields)."""
    tables = list(tables)
    if not tables:
        return np.empty(0, dtype=blob_dtype())
    return np.concatenate(tables)


def to_pandas(table):
    """A blob table (or an iterable of them, such as neopipe.run(...)) as a pandas DataFrame.

    Needs pandas (Debian: python3-pandas); the columns keep their names and types.
    """
    try:
        import pandas as pd
    except ImportError as e:
        raise ImportError("neopipe.to_pandas needs pandas (Debian: apt-get install python3-pandas)") from e
    if not isinstance(table, np.ndarray):
        table = concat(table)
    return pd.DataFrame.from_records(table)
