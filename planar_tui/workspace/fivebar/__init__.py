"""The five-bar (2-DOF RRRRR): its robot table, the ``[[workspace5r]]`` job, its
singularities and tolerance bounds."""
