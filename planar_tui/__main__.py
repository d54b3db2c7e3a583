"""``python -m planar_tui`` runs the CLI (through the same entry point as ``planar-tui``)."""

from planar_tui.entry import main

main()
