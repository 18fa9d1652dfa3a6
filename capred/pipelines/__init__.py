"""One module per command: read, compute, and assemble a result object."""
