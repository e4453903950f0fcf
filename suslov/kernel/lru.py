"""A bounded least-recently-used cache for the generated module's per-(p, d) coefficient tables.

The float and mpmath paths cache the series coefficients of a (p, d) pair because a user evaluates
many t for one body; a sweep over many bodies must not grow them without bound (issue 27: 20,000
distinct d at p = 15 held 126 MB).  A dict-like object: ``key in cache``, ``cache[key]``,
``cache[key] = value``; reads refresh a key, writes beyond ``maxsize`` evict the oldest.
"""
from __future__ import annotations

from collections import OrderedDict

__all__ = ["BoundedCache"]


class BoundedCache:
    """At most ``maxsize`` entries, least recently used evicted first.

    >>> c = BoundedCache(2); c["a"] = 1; c["b"] = 2; _ = c["a"]; c["c"] = 3
    >>> sorted(c.keys())
    ['a', 'c']
    """

    def __init__(self, maxsize: int):
        if maxsize < 1:
            raise ValueError(f"maxsize={maxsize}: must be at least 1")
        self.maxsize, self._data = maxsize, OrderedDict()

    def __contains__(self, key) -> bool:
        return key in self._data

    def __getitem__(self, key):
        self._data.move_to_end(key)
        return self._data[key]

    def __setitem__(self, key, value) -> None:
        self._data[key] = value
        self._data.move_to_end(key)
        while len(self._data) > self.maxsize:
            self._data.popitem(last=False)

    def __len__(self) -> int:
        return len(self._data)

    def keys(self):
        return self._data.keys()

    def clear(self) -> None:
        self._data.clear()
