"""The numeric solve of the exported C code: the augmented system by Gaussian elimination with partial pivoting
over fixed-size arrays, the sliding rates' signs and the friction's normal forces, as ``lagsolve simulate``
solves them (:meth:`lagsolve.numeric.system.NumericSystem.solve_all` with every constraint held and every
contact sliding)."""

from __future__ import annotations

from lagsolve.numeric.system import NumericSystem


def size(count: int) -> int:
    """An array's length in C (at least 1: C has no arrays of length 0)."""
    return max(1, count)


def gauss(rows: int, columns: int, prefix: str) -> list[str]:
    """Gaussian elimination with partial pivoting over ``a[rows][rows] x = b[rows][columns]`` (b becomes x)."""
    return [
        f"static int {prefix}_gauss(double a[{rows}][{rows}], double b[{rows}][{columns}])",
        "{",
        "    int i, j, r, c;",
        f"    for (j = 0; j < {rows}; ++j) {{",
        "        int pivot = j;",
        f"        for (r = j + 1; r < {rows}; ++r)",
        "            if (fabs(a[r][j]) > fabs(a[pivot][j])) pivot = r;",
        "        if (a[pivot][j] == 0.0 || !isfinite(a[pivot][j])) return 1;",
        "        if (pivot != j) {",
        f"            for (c = 0; c < {rows}; ++c) {{",
        "                double s = a[j][c]; a[j][c] = a[pivot][c]; a[pivot][c] = s;", "            }",
        f"            for (c = 0; c < {columns}; ++c) {{",
        "                double s = b[j][c]; b[j][c] = b[pivot][c]; b[pivot][c] = s;", "            }",
        "        }",
        f"        for (r = j + 1; r < {rows}; ++r) {{",
        "            double f = a[r][j] / a[j][j];",
        "            if (f == 0.0) continue;",
        f"            for (c = j; c < {rows}; ++c) a[r][c] -= f * a[j][c];",
        f"            for (c = 0; c < {columns}; ++c) b[r][c] -= f * b[j][c];",
        "        }",
        "    }",
        f"    for (i = {rows} - 1; i >= 0; --i) {{",
        f"        for (c = 0; c < {columns}; ++c) {{",
        "            double s = b[i][c];",
        f"            for (j = i + 1; j < {rows}; ++j) s -= a[i][j] * b[j][c];",
        "            b[i][c] = s / a[i][i];",
        "        }",
        "    }",
        "    return 0;",
        "}",
        "",
    ]


def sigma(system: NumericSystem, prefix: str) -> list[str]:
    """``<prefix>_sigma``: each contact's sliding rate σ = w·q̇ (0 for a contact that slides in a plane)."""
    n, k = system.n, len(system.contacts)
    lines = [f"static void {prefix}_sigma(double t, const double *y, const double *p, double *sigma)", "{",
             f"    double w[{size(len(system.expressions['sliding']))}];", "    int i;",
             f"    {prefix}_sliding(t, y, p, w);", "    (void)i;"]
    at = 0
    for c in range(k):
        lines.append(f"    sigma[{c}] = 0.0;")
        if system.sticks[c]:
            lines.append(f"    for (i = 0; i < {n}; ++i) sigma[{c}] += w[{at} + i] * y[{n} + i];")
            at += 2 * n + 1
    return [*lines, "}", ""]


def solve(system: NumericSystem, prefix: str) -> list[str]:
    """``<prefix>_solve``: q̈, λ and the normal forces N at (t, y); ``signs`` scales the forcing's columns."""
    n, m, k = system.n, system.m, len(system.contacts)
    rows, columns = n + m, k + 1
    at = n * n + n * columns
    lines = [
        f"static int {prefix}_solve(double t, const double *y, const double *p, const double *signs, double *qdd,",
        "                        double *lam, double *normal)", "{",
        f"    double flat[{size(len(system.expressions['matrices']))}];",
        f"    double a[{rows}][{rows}];", f"    double b[{rows}][{columns}];", "    int i, j, c;",
        f"    {prefix}_matrices(t, y, p, flat);",
        "    memset(a, 0, sizeof a);", "    memset(b, 0, sizeof b);",
        f"    for (i = 0; i < {n}; ++i) {{",
        f"        for (j = 0; j < {n}; ++j) a[i][j] = flat[i * {n} + j];",
        f"        for (c = 0; c < {columns}; ++c) b[i][c] = flat[{n * n} + i * {columns} + c] * signs[c];",
        "    }",
    ]
    if m:
        lines += [f"    for (i = 0; i < {m}; ++i) {{",
                  f"        for (j = 0; j < {n}; ++j) {{",
                  f"            a[j][{n} + i] = -flat[{at} + i * {n} + j];",
                  f"            a[{n} + i][j] = flat[{at} + i * {n} + j];", "        }",
                  f"        b[{n} + i][0] = flat[{at + m * n} + i];", "    }"]
    lines += [f"    if ({prefix}_gauss(a, b)) return 1;"]
    lines += [f"    if ({prefix}_normal_forces(t, y, p, b, normal)) return 2;"] if k else ["    (void)normal;"]
    lines += [f"    for (i = 0; i < {rows}; ++i) {{", "        double s = b[i][0];",
              f"        for (c = 1; c < {columns}; ++c) s += b[i][c] * normal[c - 1];",
              f"        if (i < {n}) qdd[i] = s; else lam[i - {n}] = s;", "    }", "    return 0;", "}", ""]
    return lines


def normal_forces(system: NumericSystem, prefix: str) -> list[str]:
    """``<prefix>_normal_forces``: N = |a + B N| per contact from the solved columns (a quadratic for one
    contact, a fixed-point iteration for several)."""
    n, m, k = system.n, system.m, len(system.contacts)
    if not k:
        return []
    dims = max(d for contact in system.contacts for _, _, d in contact)
    lines = [f"static int {prefix}_normal_forces(double t, const double *y, const double *p,",
             f"                                double b[{n + m}][{k + 1}], double *normal)", "{",
             f"    double u[{size(len(system.expressions['directions']))}];",
             f"    double av[{k}][{dims}];", f"    double bv[{k}][{dims}][{k}];", "    int c, d, e, it;",
             f"    {prefix}_directions(t, y, p, u);", "    memset(av, 0, sizeof av);", "    memset(bv, 0, sizeof bv);"]
    for c, contact in enumerate(system.contacts):
        for j, offset, d in contact:
            lines += [f"    for (d = 0; d < {d}; ++d) {{",
                      f"        av[{c}][d] += b[{n + j}][0] * u[{offset} + d];",
                      f"        for (e = 0; e < {k}; ++e) bv[{c}][d][e] += u[{offset} + d] * b[{n + j}][1 + e];",
                      "    }"]
    lines += [f"    for (c = 0; c < {k}; ++c) {{", "        double s = 0.0;",
              f"        for (d = 0; d < {dims}; ++d) s += av[c][d] * av[c][d];",
              "        normal[c] = sqrt(s);", "    }"]
    if k == 1:
        lines += ["    (void)it;", "    {", "        double bb = 0.0, ab = 0.0, aa = 0.0;",
                  f"        for (d = 0; d < {dims}; ++d) {{",
                  "            bb += bv[0][d][0] * bv[0][d][0];", "            ab += av[0][d] * bv[0][d][0];",
                  "            aa += av[0][d] * av[0][d];", "        }",
                  "        if (bb >= 1.0) return 2;  /* no unique normal force (Painleve-type) */",
                  "        normal[0] = (ab + sqrt(ab * ab + (1.0 - bb) * aa)) / (1.0 - bb);", "    }",
                  "    return 0;", "}", ""]
        return lines
    lines += ["    for (it = 0; it < 100; ++it) {", f"        double fresh[{k}], change = 0.0, largest = 1.0;",
              f"        for (c = 0; c < {k}; ++c) {{", "            double s = 0.0;",
              f"            for (d = 0; d < {dims}; ++d) {{", "                double x = av[c][d];",
              f"                for (e = 0; e < {k}; ++e) x += bv[c][d][e] * normal[e];",
              "                s += x * x;", "            }", "            fresh[c] = sqrt(s);",
              "            if (fresh[c] > largest) largest = fresh[c];", "        }",
              f"        for (c = 0; c < {k}; ++c) {{",
              "            if (fabs(fresh[c] - normal[c]) > change) change = fabs(fresh[c] - normal[c]);",
              "            normal[c] = fresh[c];", "        }",
              "        if (change <= 1e-13 * largest) return 0;", "    }",
              "    return 2;  /* the normal forces did not converge */", "}", ""]
    return lines
