"""Dimensions of a problem's fields (dimensions), the problem's unit system (unit_system) and the units of its results
(result_units).
"""
