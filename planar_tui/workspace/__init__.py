"""3-RRR workspace by interval analysis (paper B): robot model, geometric reference area,
runner, character-cell map. Nothing here imports numba or shapely at module level."""
