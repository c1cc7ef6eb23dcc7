"""Argument checks in Python's terms, before anything reaches the extension: a number must be a
Python or numpy number (a ``str`` or ``bool`` is a ``TypeError`` naming the argument), a name a
``str``, a path a ``str`` or ``os.PathLike``. Ranges are the library's checks (``ValueError``
with its message, which names the argument too)."""

from __future__ import annotations

import numbers
import os
from typing import Any, Optional, Tuple, Union

import numpy as np


def _kind(value: Any) -> str:
    return type(value).__name__


def _is_number(value: Any) -> bool:
    if isinstance(value, (bool, np.bool_)):
        return False
    if isinstance(value, numbers.Real):
        return True
    # a 0-d numpy array of a real dtype, as numpy reductions return
    return isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "iuf"


def number(name: str, value: Any) -> float:
    """``value`` as a float, or ``TypeError`` naming ``name``."""
    if not _is_number(value):
        raise TypeError(
            f"{name} must be a real number (int, float or a numpy number), not {_kind(value)}"
            f" ({value!r})"
        )
    return float(value)


def optional_number(name: str, value: Any) -> Optional[float]:
    """None, or ``value`` as a float (``number``)."""
    return None if value is None else number(name, value)


def flag(name: str, value: Any) -> bool:
    """``value``, a bool (Python's or numpy's), or ``TypeError`` naming ``name``."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False, not {_kind(value)} ({value!r})")
    return bool(value)


def name(argument: str, value: Any) -> str:
    """``value``, a ``str``, or ``TypeError`` naming ``argument``."""
    if not isinstance(value, str):
        raise TypeError(f"{argument} must be a str, not {_kind(value)} ({value!r})")
    return value


def optional_path(argument: str, value: Any) -> Optional[str]:
    """None, or ``value`` (a ``str`` or ``os.PathLike``) as a ``str``."""
    if value is None:
        return None
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(
            f"{argument} must be a path (str or os.PathLike), not {_kind(value)} ({value!r})"
        )
    return os.fspath(value)


def mesh(value: Any) -> Optional[str]:
    """``mesh``: None, a level name (str) or an element count (int), as the command line's text."""
    if value is None or isinstance(value, str):
        return value
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError(
            "mesh must be \"coarse\", \"default\", \"fine\" or an int (elements along the face),"
            f" not {_kind(value)} ({value!r})"
        )
    return str(int(value))


def optional_count(argument: str, value: Any) -> Optional[int]:
    """None, or ``value``, an int >= 1 (Python's or numpy's), or ``TypeError`` / ``ValueError``
    naming ``argument``."""
    if value is None:
        return None
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{argument} must be an int, not {_kind(value)} ({value!r})")
    if not (1 <= int(value) < 2**63):
        raise ValueError(f"{argument} = {value!r} is out of range; allowed: an int >= 1")
    return int(value)


def max_memory(value: Any) -> Optional[int]:
    """``max_memory``: None or a number of bytes (int or float, >= 0)."""
    if value is None:
        return None
    amount = number("max_memory", value)
    if not (amount >= 0 and amount < 2**63):
        raise ValueError(f"max_memory = {value!r} is out of range; allowed: bytes in [0, 2^63)")
    return int(amount)


ArrayLike = Union[float, "np.ndarray", Any]


def values(argument: str, value: ArrayLike) -> Tuple[np.ndarray, Tuple[int, ...]]:
    """The values as a contiguous 1-D float64 array and the shape to give the results, or
    ``TypeError`` naming ``argument`` when they are not numbers (strings, bools, objects)."""
    try:
        array = np.asarray(value)
    except (TypeError, ValueError) as e:  # ragged nesting and the like
        raise TypeError(f"{argument} must be numbers or an array of them: {e}") from None
    if array.dtype.kind not in "iuf":
        raise TypeError(
            f"{argument} must be numbers or an array of them (int or float),"
            f" not {_describe(array, value)}"
        )
    array = array.astype(np.float64)
    return np.ascontiguousarray(array.ravel()), array.shape


def _describe(array: np.ndarray, value: Any) -> str:
    kinds = {"b": "bool", "U": "str", "S": "bytes", "O": "objects", "c": "complex",
             "M": "datetime", "m": "timedelta"}
    what = kinds.get(array.dtype.kind, str(array.dtype))
    return f"{what} ({value!r})"
