"""Dialogs and the help screen of the workbench."""
