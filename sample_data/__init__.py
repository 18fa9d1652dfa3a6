"""Bundled synthetic sample data for capred (see README.md in this folder)."""
