"""Section readers of the problem file, combined by :mod:`lagsolve.problem.load`."""
