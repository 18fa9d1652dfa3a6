"""Reading lab CSV files into SI arrays and writing result files."""
