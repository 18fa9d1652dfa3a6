"""Numpy-free declarations of capred: registries' metadata, their numerical callables named as ``"module:function"``."""

from .callables import resolve  # noqa: F401  (one resolver of "module:function" references)
