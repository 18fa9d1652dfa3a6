"""Numerical callables named as ``"module:function"`` in numpy-free declarations, and their one resolver.

A registry entry names the function that computes it as a string (as `capred.reductions` names each command's
pipeline), so that importing the declaration imports no numerical module; a user registering an entry from a
script may pass the function itself instead. `resolve` turns either into the callable, importing the module on
first use only.
"""

from __future__ import annotations

from functools import cache
from importlib import import_module

__all__ = ["CallableField", "ref_of", "resolve"]


@cache
def _import(ref: str):
    module, sep, name = ref.partition(":")
    if not sep or not module or not name:
        raise ValueError(f"callable reference {ref!r} is not of the form 'module:function'")
    obj = import_module(module)
    for part in name.split("."):
        try:
            obj = getattr(obj, part)
        except AttributeError:
            raise ValueError(f"callable reference {ref!r}: module {module!r} has no {name!r}") from None
    if not callable(obj):
        raise ValueError(f"callable reference {ref!r} names {type(obj).__name__}, not a function")
    return obj


def resolve(ref):
    """The callable named by ``ref``: a ``"module:function"`` string (imported once, cached) or a callable.

    Parameters
    ----------
    ref : str, callable or None
        ``"package.module:function"`` (a dotted attribute path after the colon is allowed), a callable (returned
        as it is) or None (returned as None).

    Returns
    -------
    callable or None

    Raises
    ------
    ValueError
        For a string not of the form ``module:function``, or naming nothing callable.
    ModuleNotFoundError
        When the module does not exist.
    """
    if ref is None or callable(ref):
        return ref
    if isinstance(ref, str):
        return _import(ref)
    raise ValueError(f"a callable or a 'module:function' string is needed, not {type(ref).__name__}")


class CallableField:
    """A dataclass field holding a callable given as ``"module:function"`` or as the callable itself.

    Reading the attribute gives the callable (resolved on first read, see `resolve`); `ref_of` gives what was
    declared, without importing anything. ``shape`` says what the field holds: ``"one"`` a callable (or None),
    ``"pairs"`` a tuple of ``(name, callable)`` pairs, ``"second"`` a ``(name, callable)`` pair (or None).
    """

    def __init__(self, default=None, shape: str = "one"):
        self.default = default
        self.shape = shape

    def __set_name__(self, owner, name):
        self.name = name
        self.slot = "_ref_" + name

    def __get__(self, obj, owner=None):
        if obj is None:
            return self.default
        raw = obj.__dict__.get(self.slot, self.default)
        if self.shape == "pairs":
            return tuple((k, resolve(f)) for k, f in raw)
        if self.shape == "second":
            return None if raw is None else (raw[0], resolve(raw[1]))
        return resolve(raw)

    def __set__(self, obj, value):
        if value is self:  # not given: dataclasses pass the field's default, this descriptor
            value = self.default
        if self.shape == "pairs":
            value = tuple(tuple(p) for p in value)
        obj.__dict__[self.slot] = value


def ref_of(entry, name: str):
    """What an entry declares for its callable field ``name``, without importing the function's module.

    The field holds a ``"module:function"`` string, a callable or None.

    Parameters
    ----------
    entry : object
        A registry entry (a dataclass with `CallableField` fields).
    name : str
        The field's name, e.g. ``"sigma_eff"``.

    Returns
    -------
    str, callable, tuple or None
        As declared.
    """
    descriptor = next((vars(c)[name] for c in type(entry).__mro__ if name in vars(c)), None)
    if isinstance(descriptor, CallableField):
        return entry.__dict__.get(descriptor.slot, descriptor.default)
    return getattr(entry, name)
