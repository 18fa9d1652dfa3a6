"""Pure, vectorised physics. SI units in and out; imports only numpy/scipy."""
