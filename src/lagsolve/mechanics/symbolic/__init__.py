"""SymPy-level algebra the stages share: fast factoring and counting (algebra), display simplification (simplify), zero
proofs (identities), structured linear solves (linsolve, ringsolve), signs and partial derivatives.
"""
