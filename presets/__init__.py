"""planar-tui's bundled presets (TOML), installed as ``planar_tui.bundled_presets``."""
