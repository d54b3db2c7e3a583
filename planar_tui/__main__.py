"""``python -m planar_tui`` runs the CLI."""

from planar_tui.cli import main

main()
