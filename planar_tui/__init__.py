"""planar-tui: a terminal workbench for planar robots.

NOC dynamics of n-link planar serial robots, Sobol/eFAST sensitivity of their joint
torques, and the 3-RRR workspace by interval analysis, as a batch CLI and a Textual app.
"""

__version__ = "0.1.0"
