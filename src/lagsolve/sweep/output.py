"""A sweep's table as Parquet or CSV bytes (the CLI writes them through :mod:`lagsolve.files`).

Parquet keeps list columns (event times, Poincaré crossings) as lists of doubles; CSV writes
each list as a JSON array in one cell (``[0.5, 1.25]``), numbers with Python's shortest repr.
"""

from __future__ import annotations

import json
from typing import Any

from lagsolve.errors import Issue, SpecError
from lagsolve.sweep import INSTALL

SUFFIXES = (".parquet", ".csv")


def table_bytes(frame: Any, suffix: str) -> bytes:
    """The frame as the bytes of a ``.parquet`` or ``.csv`` file.

    Raises
    ------
    SpecError
        Another suffix.
    ImportError
        Parquet without pyarrow.
    """
    if suffix == ".csv":
        flat = frame.copy()
        for column in flat.columns:
            if flat[column].dtype == object and len(flat) and isinstance(flat[column].iloc[0], list):
                flat[column] = [json.dumps(v) for v in flat[column]]
        return str(flat.to_csv(index=False, lineterminator="\n")).encode("utf-8")
    if suffix == ".parquet":
        try:
            import pyarrow  # noqa: F401
        except ImportError as exc:
            raise ImportError(f"Parquet output needs pyarrow: {INSTALL}; or write .csv") from exc
        import io

        buffer = io.BytesIO()
        frame.to_parquet(buffer, index=False)
        return buffer.getvalue()
    raise SpecError([Issue("<command line>", 0, "-o/--output", f"unknown table format {suffix!r}",
                           "name the output FILE.parquet or FILE.csv")])
