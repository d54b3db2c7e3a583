"""The 3-RRR (paper B): its robot table, the ``[workspace]`` job, its interval forms
(joint bisection, leg-wise paving, arc-distance), singularities, orientation ranges and
exact reference."""
