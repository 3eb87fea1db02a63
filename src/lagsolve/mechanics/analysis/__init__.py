"""The analysis after the equations (analyse): integrability, minimal coordinates, conserved quantities and symmetries,
the effective potential, steady motions, equilibria and normal modes.
"""
