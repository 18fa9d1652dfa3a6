"""Least-squares fits returning result objects with uncertainties."""
