"""Runners: one function per job kind, ``run(job, progress) -> JobResult``.

Runners import the Numba kernels lazily, work in chunks, report through
:class:`~planar_tui.progress.Progress` and never write files: the CLI and the app do.
"""
