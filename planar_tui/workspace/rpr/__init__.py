"""The 3-RPR: its robot table, the ``[[workspace3rpr]]`` job (annulus leg test), its
singularities, orientation ranges and tolerance bounds."""
