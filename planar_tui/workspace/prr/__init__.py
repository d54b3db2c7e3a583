"""The 3-PRR: its robot table, the ``[[workspace3prr]]`` job (slider leg test), its
singularities, orientation ranges and tolerance bounds."""
