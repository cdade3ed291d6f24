"""The ``seatwin`` command line: one module per verb (group), registered in :mod:`seatwin.cli.main`."""
