"""Figures (matplotlib, no pyplot state) and console tables (rich)."""
