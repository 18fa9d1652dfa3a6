"""``python -m capred``: the command line, as the ``capred`` script runs it."""

from .cli import main

main()
