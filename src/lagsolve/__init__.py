"""lagsolve: Lagrangian mechanics from a YAML problem file.

The pipeline is ``problem`` (read and validate) → ``mechanics`` (derive) →
``render`` (Markdown, LaTeX, JSON). Importing this package is cheap: SymPy is
imported only by the modules that need it.
"""

__version__ = "0.1.0"
