"""Checking a derivation against its problem's expected answers.

:mod:`.compare` gives the verdicts (symbolic, then numeric), :mod:`.states` finds the states on the
constraint surface where answers are compared numerically, and :mod:`.diagnose` says why an answer
that differs differs (a sign, a factor, a convention). The public function is :func:`lagsolve.check`.
"""
