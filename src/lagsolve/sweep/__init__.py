"""Many runs of one problem (see :mod:`lagsolve.sweep.api`); this module holds only what its modules share."""

#: how to install what the distributed runs and the Parquet output need, for messages
INSTALL = "pip install 'lagsolve[sweep]' (or: pip install 'dask[distributed]' pyarrow numba)"
