"""``python -m planar_tui`` runs the CLI (through the same entry point as ``planar-tui``).

Guarded: a Dask local cluster's worker processes are spawned, and spawning imports the
parent's main module again (as ``__mp_main__``), which must not start a second CLI."""

from planar_tui.entry import main

if __name__ == "__main__":
    main()
