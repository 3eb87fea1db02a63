"""Orchestration: what each command runs, under a CPU budget, in a child process.

:mod:`.pipeline` has one entry point per command (derive, check, simulate, golden), :mod:`.simulation`
one simulation run from the matrix form to tables and figures, :mod:`.budget` the budgeted child
process. Nothing here prints, exits or writes files; the command line (:mod:`lagsolve.cli`) does.
"""
