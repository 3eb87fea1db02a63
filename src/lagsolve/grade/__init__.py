"""``lagsolve grade``: worked solutions graded step by step against a key problem (issue 31).

:mod:`.submission` reads a submission (the contract: ``docs/grading.md``) through the problem format's
expression gateway; :mod:`.key` reads the key's ``grading:`` section; :mod:`.grader` grades the steps
with ``lagsolve check``'s comparisons (:mod:`lagsolve.check.compare`; the steps past the core, equilibria,
frequencies and H, with :mod:`.analysis_steps`), the named mistakes with :mod:`.mistakes`, follow-through with
:mod:`.follow`, other coordinates with :mod:`.frame`; :mod:`lagsolve.render.grades` writes the
grades and the class summary.
Nothing here prints or exits.
"""
