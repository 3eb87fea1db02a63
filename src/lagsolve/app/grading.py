"""``lagsolve grade``: the key derived once, every submission read and graded (:mod:`lagsolve.grade`).

A submission that cannot be read at all gets a grade with every step ``unreadable`` and its error; the rest of
the class is graded. A bad key raises :class:`~lagsolve.errors.SpecError` (exit 2).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from lagsolve.errors import SpecError

if TYPE_CHECKING:
    from lagsolve.grade.grader import ClassGrades, SubmissionGrade


def grade_files(key: str | Path, submissions: Sequence[str | Path], *, budget: float | None = None,
                seed: int = 0) -> ClassGrades:
    """Grade each submission file against the key problem file ``key``.

    Raises
    ------
    SpecError
        The key is not a valid problem file, or its ``grading:`` section is malformed.
    """
    from lagsolve.grade.follow_analysis import FAILURES
    from lagsolve.grade.grader import ClassGrades, GradingKey, grade, unreadable_grade
    from lagsolve.grade.key import read_grading
    from lagsolve.grade.submission import read_submission
    from lagsolve.mechanics.derivation import derive
    from lagsolve.problem.load import load_problem

    problem = load_problem(key)
    grading = read_grading(key, problem)
    derivation = derive(problem, budget=budget)
    context = GradingKey(derivation, grading, seed)
    normals = {f.term.normal.name: f.term.normal for f in derivation.friction}
    grades = []
    for path in submissions:
        try:
            submission = read_submission(path, problem, normals)
        except SpecError as error:
            grades.append(unreadable_grade(Path(path).stem, str(path), str(error.issues[0]), grading))
            continue
        except FAILURES as error:  # text the gateway let through but SymPy cannot take: this file, not the class
            message = f"{path}: the submission could not be read ({type(error).__name__}); check its expressions"
            grades.append(unreadable_grade(Path(path).stem, str(path), message, grading))
            continue
        grades.append(grade(derivation, grading, submission, seed=seed, key=context))
    return ClassGrades(problem.name, str(key), tuple(grades))


def student_folder(student: str) -> str:
    """The folder name of a student id: the id itself where it is a safe name (letters, digits, ``_``, ``-``,
    ``.`` inside), else its safe letters and a short hash of the whole id, so that ids that differ only in what a
    path cannot hold stay apart (``王小明`` and ``李雷`` gave the one folder ``problem``, ``a/b`` and ``c/b`` ``b``).

    >>> student_folder("ada"), student_folder("a/b") != student_folder("c/b")
    ('ada', True)
    >>> student_folder("王小明")
    'student_acf979cc'
    """
    import hashlib
    import re

    if re.fullmatch(r"[A-Za-z0-9_-]+(\.[A-Za-z0-9_-]+)*", student):
        return student
    safe = re.sub(r"[^A-Za-z0-9_-]+", "_", student).strip("_") or "student"
    return f"{safe}_{hashlib.sha256(student.encode('utf-8')).hexdigest()[:8]}"


def gradescope_folders(grades: Sequence[SubmissionGrade]) -> dict[str, SubmissionGrade]:
    """Each submission's folder of ``lagsolve grade --format gradescope -o DIR`` (its student id made safe for a
    path), by folder.

    Raises
    ------
    SpecError
        When two submissions would write the same folder (the same ``student:``, or ids such as ``a/b`` and
        ``c/b`` that give the same folder name): one student's results would silently replace another's.
    """
    from lagsolve.errors import Issue

    folders: dict[str, SubmissionGrade] = {}
    by_case: dict[str, str] = {}  # a folder's name without case: macOS and Windows do not tell Alice from alice
    issues = []
    for g in grades:
        folder = student_folder(g.student)
        seen = by_case.get(folder.casefold())
        if seen is not None:
            first = folders[seen]
            same = "" if seen == folder else f" on a file system that ignores case ({seen!r})"
            issues.append(Issue(g.source, 0, "student", f"the student id {g.student!r} gives the results folder "
                                f"{folder!r}, as {first.student!r} of {first.source} does{same}: one would replace "
                                "the other", "give each submission a distinct student id (student: ...)"))
            continue
        folders[folder] = g
        by_case[folder.casefold()] = folder
    if issues:
        raise SpecError(issues)
    return folders
