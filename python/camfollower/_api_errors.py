# SPDX-License-Identifier: BSD-3-Clause
"""Short, named errors for calls into the compiled core that match none of its signatures.

pybind11 answers such a call with every overload and the repr of every argument it was given (an
array prints whole: thousands of characters). :func:`install` wraps the core's public functions,
methods, constructors and property setters once, at import, so that the TypeError names the call,
the types (and shapes) it got and the signature(s) it takes, in a few lines.
"""

from __future__ import annotations

import functools
import inspect
import re

_MISMATCH = re.compile(r"incompatible (function|constructor) arguments")
_SIGNATURE = re.compile(r"^\s*\d+\. (.*)$", re.MULTILINE)
_MAX_SIGNATURE = 300


def _describe(value) -> str:
    """A value as a type (with its shape, or the value itself when short), never a long repr."""
    kind = type(value).__name__
    shape = getattr(value, "shape", None)
    if isinstance(shape, tuple):
        return f"{kind} of shape {shape}"
    if isinstance(value, (bool, int, float, complex, str)) and len(repr(value)) <= 32:
        return f"{kind} {value!r}"
    if isinstance(value, (list, tuple, dict, set)):
        return f"{kind} of {len(value)} items"
    if isinstance(value, int):
        return f"int of {value.bit_length()} bits (beyond a float's range)"
    return kind


# pybind11's typing spelled the way a user reads it.
_PLAIN = [
    ("typing.Annotated[numpy.typing.ArrayLike, numpy.float64]", "array"),
    ("typing.Annotated[numpy.typing.NDArray[numpy.float64], \"[m, 1]\"]", "array"),
    ("typing.SupportsInt | typing.SupportsIndex", "int"),
    ("typing.SupportsFloat | typing.SupportsIndex", "float"),
    ("collections.abc.Sequence", "Sequence"),
    ("camfollower._core.", ""),
    ("typing.", ""),
]


def _plain(signature: str, skip_self: bool) -> str:
    for long, short in _PLAIN:
        signature = signature.replace(long, short)
    if skip_self:  # the bound instance: "self: X" for methods, "arg0: X" for property setters
        signature = re.sub(r"^\((self|arg0): [^,)]*(, )?", "(", signature)
    return signature if len(signature) <= _MAX_SIGNATURE else signature[:_MAX_SIGNATURE] + " ..."


def _rewrite(error: TypeError, name: str, args, kwargs, skip_self: bool) -> TypeError | None:
    text = str(error)
    if not _MISMATCH.search(text):
        return None
    signatures = [_plain(sig, skip_self) for sig in _SIGNATURE.findall(text)]
    got = ", ".join([_describe(a) for a in args] + [f"{k}={_describe(v)}" for k, v in kwargs.items()])
    takes = "; or ".join(f"{name}{s}" for s in signatures) or "see help()"
    return TypeError(f"{name}(): the arguments ({got}) match none of its signatures: {takes}")


def _wrap(function, name: str, skip_self: bool):
    @functools.wraps(function)
    def call(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except TypeError as e:
            short = _rewrite(e, name, args[1:] if skip_self else args, kwargs, skip_self)
            if short is None:
                raise
            raise short from None

    return call


def install(module) -> None:
    """Wrap the public callables of a pybind11 module in place (idempotent)."""
    if getattr(module, "_api_errors_installed", False):
        return
    for name, obj in list(vars(module).items()):
        if name.startswith("_") and name != "__init__":
            continue
        if inspect.isclass(obj) and obj.__module__ == module.__name__:
            for attr, member in list(vars(obj).items()):
                if attr.startswith("_") and attr != "__init__":
                    continue
                qualified = f"{obj.__name__}" if attr == "__init__" else f"{obj.__name__}.{attr}"
                if type(member).__name__ == "instancemethod":
                    setattr(obj, attr, _wrap(member.__func__, qualified, skip_self=True))
                elif isinstance(member, staticmethod):
                    setattr(obj, attr, staticmethod(_wrap(member.__func__, qualified, skip_self=False)))
                elif isinstance(member, property) and member.fset is not None:
                    setattr(
                        obj,
                        attr,
                        property(
                            member.fget, _wrap(member.fset, qualified, skip_self=True), member.fdel, member.__doc__
                        ),
                    )
        elif type(obj).__name__ == "builtin_function_or_method":
            setattr(module, name, _wrap(obj, name, skip_self=False))
    module._api_errors_installed = True
