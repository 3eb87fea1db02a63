"""The core equations: the model (coordinates, T, V), constraints, forces, friction terms, reactions, inertia,
Lagrange's equations and the matrix form they make (matrix_form).
"""
