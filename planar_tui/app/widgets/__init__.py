"""Widgets and panes of the workbench."""
