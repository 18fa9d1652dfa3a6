"""Numpy-free declarations of capred: registries' metadata, their numerical callables named as ``"module:function"``."""
